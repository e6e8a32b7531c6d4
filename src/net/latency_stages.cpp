#include "telear/net/latency_stages.hpp"

namespace telear::net {

void LatencySeries::add(const StageLatency& latency) {
  for (std::size_t i = 0; i < kLatencyStageCount; ++i) {
    seconds[i].push_back(kLatencyStages[i].of(latency));
  }
}

StageSummaries LatencySeries::summarize() const {
  StageSummaries summaries;
  for (std::size_t i = 0; i < kLatencyStageCount; ++i) {
    summaries[i] = summarize_latency(seconds[i]);
  }
  return summaries;
}

}  // namespace telear::net
