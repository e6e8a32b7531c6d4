// `telear bench render`: the table's shape and the seed's figures beside ours, and its
// error messages. Timings are printed, never asserted.

#include "bench/render_bench_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

namespace telear::cli {
namespace {

using ::testing::HasSubstr;

TEST(RenderBenchCommandTest, CasesCoverTheSeedsTables) {
  const auto cases = render_bench_cases();
  ASSERT_EQ(cases.size(), 20u);  // 5 cases x {graphics, video} x {mono, stereo}
  int with_seed = 0;
  for (const RenderBenchCase& c : cases) with_seed += !c.seed.empty();
  EXPECT_GE(with_seed, 5);
  EXPECT_EQ(cases[0].name, "graphics, no drawing");
  EXPECT_EQ(cases[0].seed, "273.4 fps");
}

TEST(RenderBenchCommandTest, PrintsATableBesideTheSeedsFigures) {
  RenderBenchOptions options;
  options.seconds = 0.02;
  options.width = 64;
  options.height = 48;
  options.only = "arm, 8 seg";
  std::ostringstream out, err;
  ASSERT_EQ(run_bench_render(options, out, err), 0) << err.str();
  EXPECT_THAT(out.str(), HasSubstr("| case | view | fps | ms/frame | CPU ms/frame | seed |"));
  EXPECT_THAT(out.str(), HasSubstr("| graphics, arm, 8 seg | mono |"));
  EXPECT_THAT(out.str(), HasSubstr("253.6 fps, 64.1 ms"));
  EXPECT_THAT(out.str(), HasSubstr("| video, arm, 8 seg | stereo |"));
  EXPECT_THAT(out.str(), HasSubstr("device: EGL"));
}

TEST(RenderBenchCommandTest, JsonHasOneEntryPerCase) {
  RenderBenchOptions options;
  options.seconds = 0.01;
  options.width = 32;
  options.height = 32;
  options.only = "no drawing";
  options.json = true;
  std::ostringstream out, err;
  ASSERT_EQ(run_bench_render(options, out, err), 0) << err.str();
  EXPECT_THAT(out.str(), HasSubstr("\"cpu_ms_per_frame\""));
  EXPECT_THAT(out.str(), HasSubstr("\"name\": \"video, no drawing\""));
}

TEST(RenderBenchCommandTest, BadArgumentsGetOneClearLine) {
  std::ostringstream out, err;
  RenderBenchOptions bad_seconds;
  bad_seconds.seconds = 0;
  EXPECT_EQ(run_bench_render(bad_seconds, out, err), 2);
  EXPECT_EQ(err.str(), "telear bench render: --seconds must be in (0, 600], got 0\n");
  err.str("");
  RenderBenchOptions no_match;
  no_match.seconds = 0.01;
  no_match.width = 16;
  no_match.height = 16;
  no_match.only = "teapot";
  EXPECT_EQ(run_bench_render(no_match, out, err), 2);
  EXPECT_EQ(err.str(), "telear bench render: no case matches 'teapot'\n");
}

}  // namespace
}  // namespace telear::cli
