#pragma once
// The six latency stages of the video path, in one table: every place that lists them (the
// session's status, the console's status panel, `telear bench stream`, the demo's report)
// iterates kLatencyStages instead of naming the stages by hand.
//
// Per frame, in seconds, on the client's clock (server stamps converted with the ping's
// clock-offset estimate, telear/net/clock_offset.hpp):
//
//   key                from -> to                                               clock
//   capture_to_encode  pair captured (the later eye) -> encode start            server
//   encode             encode start -> encode end (both eyes)                   server
//   send_queue         encode end -> handed to gRPC for this client             server
//   network            server send -> received by the client                    both
//   decode             received -> both eyes decoded                            client
//   total              pair captured -> decoded (the image's age when shown)    both
//
// The first five add up to the total. VisionClient (telear/net/vision_client.hpp) fills a
// StageLatency per decoded frame; LatencySeries collects them and summarizes each stage
// with the nearest-rank percentiles of telear/net/latency_summary.hpp.

#include <array>
#include <cstddef>
#include <vector>

#include "telear/net/latency_summary.hpp"

namespace telear::net {

// One frame's stages, in seconds (see the table above).
struct StageLatency {
  double capture_to_encode_s = 0, encode_s = 0, send_queue_s = 0, network_s = 0, decode_s = 0;
  double total_s = 0;  // capture -> decoded
};

struct LatencyStage {
  const char* key;         // JSON key and identifier: "capture_to_encode" ... "total"
  const char* label;       // short label for tables: "capture -> encode" ... "capture -> decoded"
  const char* long_label;  // with what it spans: "encode (both eyes)", "total capture -> decoded"
  double StageLatency::*seconds;  // where a StageLatency holds it

  double of(const StageLatency& latency) const { return latency.*seconds; }
};

inline constexpr std::array<LatencyStage, 6> kLatencyStages = {{
    {"capture_to_encode", "capture -> encode", "capture -> encode",
     &StageLatency::capture_to_encode_s},
    {"encode", "encode", "encode (both eyes)", &StageLatency::encode_s},
    {"send_queue", "send queue", "send queue", &StageLatency::send_queue_s},
    {"network", "network", "network", &StageLatency::network_s},
    {"decode", "decode", "decode (both eyes)", &StageLatency::decode_s},
    {"total", "capture -> decoded", "total capture -> decoded", &StageLatency::total_s},
}};
inline constexpr std::size_t kLatencyStageCount = kLatencyStages.size();
// The index of the total (capture -> decoded), the figure targets are set on.
inline constexpr std::size_t kTotalLatencyStage = kLatencyStageCount - 1;

// One summary per stage, in kLatencyStages' order.
using StageSummaries = std::array<LatencySummary, kLatencyStageCount>;

// Per-stage series of seconds, in kLatencyStages' order (seconds[i] is stage i's samples).
struct LatencySeries {
  std::array<std::vector<double>, kLatencyStageCount> seconds;

  void add(const StageLatency& latency);
  std::size_t size() const { return seconds[0].size(); }
  StageSummaries summarize() const;  // p50 / p99 / count of each stage
};

}  // namespace telear::net
