// The small shared pieces of net: the random token, the latency-stage table and the servers'
// log-level words.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "telear/net/latency_stages.hpp"
#include "telear/net/random_token.hpp"
#include "telear/net/server_log.hpp"

namespace telear::net {
namespace {

using ::testing::ElementsAre;
using ::testing::MatchesRegex;

TEST(RandomToken, IsLowerCaseHexOfTwiceTheBytes) {
  EXPECT_THAT(random_token(), MatchesRegex("[0-9a-f]{32}"));
  EXPECT_THAT(random_token(1), MatchesRegex("[0-9a-f]{2}"));
  EXPECT_THAT(random_token(5), MatchesRegex("[0-9a-f]{10}"));  // not a whole 32-bit word
  EXPECT_THAT(random_token(64), MatchesRegex("[0-9a-f]{128}"));
}

TEST(RandomToken, DiffersFromCallToCall) {
  std::set<std::string> seen;
  for (int i = 0; i < 200; ++i) seen.insert(random_token());
  EXPECT_EQ(seen.size(), 200u);
}

TEST(LatencyStages, OneTableInTheOrderOfThePath) {
  std::vector<std::string> keys, labels;
  for (const LatencyStage& stage : kLatencyStages) {
    keys.emplace_back(stage.key);
    labels.emplace_back(stage.label);
  }
  EXPECT_THAT(
      keys, ElementsAre("capture_to_encode", "encode", "send_queue", "network", "decode", "total"));
  EXPECT_THAT(labels, ElementsAre("capture -> encode", "encode", "send queue", "network", "decode",
                                  "capture -> decoded"));
  EXPECT_STREQ(kLatencyStages[kTotalLatencyStage].long_label, "total capture -> decoded");
}

TEST(LatencyStages, ReadEachStageAndSummarizeSeries) {
  const StageLatency a{0.001, 0.002, 0.003, 0.004, 0.005, 0.015};
  const StageLatency b{0.011, 0.012, 0.013, 0.014, 0.015, 0.065};
  for (std::size_t i = 0; i < kLatencyStageCount; ++i) {
    EXPECT_DOUBLE_EQ(kLatencyStages[i].of(a), i == kTotalLatencyStage ? 0.015 : 0.001 * (i + 1));
  }
  LatencySeries series;
  series.add(a);
  series.add(b);
  EXPECT_EQ(series.size(), 2u);
  const StageSummaries summaries = series.summarize();
  EXPECT_EQ(summaries[1].samples, 2);
  EXPECT_DOUBLE_EQ(summaries[1].p50_s, 0.002);  // nearest rank: the lower of two
  EXPECT_DOUBLE_EQ(summaries[1].p99_s, 0.012);
  EXPECT_DOUBLE_EQ(summaries[kTotalLatencyStage].p99_s, 0.065);
}

TEST(ServerLog, ParsesTheSixLevels) {
  EXPECT_EQ(*parse_log_level("trace"), spdlog::level::trace);
  EXPECT_EQ(*parse_log_level("debug"), spdlog::level::debug);
  EXPECT_EQ(*parse_log_level("info"), spdlog::level::info);
  EXPECT_EQ(*parse_log_level("warn"), spdlog::level::warn);
  EXPECT_EQ(*parse_log_level("error"), spdlog::level::err);
  EXPECT_EQ(*parse_log_level("off"), spdlog::level::off);
}

TEST(ServerLog, ABadLevelNamesTheValueAndTheAcceptedOnes) {
  for (const char* bad : {"warning", "INFO", "", "err"}) {
    auto level = parse_log_level(bad);
    ASSERT_FALSE(level) << bad;
    EXPECT_EQ(level.error().message, std::string("'") + bad +
                                         "' is not a log level; use one of trace, debug, info, "
                                         "warn, error, off");
  }
}

}  // namespace
}  // namespace telear::net
