// `telear bench render`: the table's shape and the seed's figures beside ours, and its
// error messages. Timings are printed, never asserted.

#include "bench/render_bench_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

namespace telear::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

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

// --mesh-arm: the arm is generated into a temporary directory (said in the output, removed
// afterwards), drawn from its URDF meshes, and set beside the PUMA's case of the same frame,
// which runs although --only selects none of the seed's cases.
TEST(RenderBenchCommandTest, MeshArmIsGeneratedDrawnAndComparedWithThePuma) {
  RenderBenchOptions options;
  options.seconds = 0.02;
  options.width = 64;
  options.height = 48;
  options.only = "mesh";
  options.mesh_arm = "ur6";
  options.mesh_detail = 8;  // small meshes: this checks the plumbing, not the speed
  std::ostringstream out, err;
  ASSERT_EQ(run_bench_render(options, out, err), 0) << err.str();
  const std::string text = out.str();
  EXPECT_THAT(text, HasSubstr("generate_arms.py --detail 8 --out "));
  EXPECT_THAT(text, HasSubstr("| video, arm, 8 seg | stereo |"));
  EXPECT_THAT(text, HasSubstr("| video, mesh ur6 (as loaded) | stereo |"));
  EXPECT_THAT(text, HasSubstr("| video, mesh ur6 (level of detail 0.50 mm) | stereo |"));
  EXPECT_THAT(text, Not(HasSubstr("| graphics,")));
  EXPECT_THAT(text, HasSubstr("mesh arm ur6: "));
  EXPECT_THAT(text, HasSubstr("x the PUMA's 'video, arm, 8 seg' stereo"));
  EXPECT_THAT(text, HasSubstr("load average: "));
  // The temporary directory named after --out is gone.
  const std::size_t at = text.find("--out ") + 6;
  const std::string directory = text.substr(at, text.find(' ', at) - at);
  ASSERT_FALSE(directory.empty());
  EXPECT_FALSE(std::filesystem::exists(directory)) << directory;

  // The JSON form carries the ratio and the mesh's size (more triangles at higher detail).
  options.json = true;
  std::ostringstream json_out;
  ASSERT_EQ(run_bench_render(options, json_out, err), 0) << err.str();
  const nlohmann::json j = nlohmann::json::parse(json_out.str());
  ASSERT_TRUE(j.contains("mesh_arm"));
  EXPECT_EQ(j["mesh_arm"]["robot"], "ur6");
  EXPECT_GT(j["mesh_arm"]["triangles"].get<long>(), 1000);
  EXPECT_GT(j["mesh_arm"]["ratio_to_baseline"].get<double>(), 0.0);
  EXPECT_GT(j["mesh_arm"]["fps_as_loaded"].get<double>(), 0.0);
  EXPECT_EQ(j["mesh_arm"]["tolerance_m"].get<double>(), 0.0005);
  EXPECT_LT(j["mesh_arm"]["triangles_drawn"].get<long>(), j["mesh_arm"]["triangles"].get<long>());
  EXPECT_EQ(j["cases"].size(), 3u);

  // --mesh-tolerance 0: the arm as loaded only.
  options.mesh_tolerance_m = 0.0;
  std::ostringstream full_out;
  ASSERT_EQ(run_bench_render(options, full_out, err), 0) << err.str();
  const nlohmann::json full = nlohmann::json::parse(full_out.str());
  EXPECT_EQ(full["cases"].size(), 2u);
  EXPECT_EQ(full["mesh_arm"]["triangles_drawn"], full["mesh_arm"]["triangles"]);
}

TEST(RenderBenchCommandTest, MeshArmErrorsNameTheProblem) {
  std::ostringstream out, err;
  RenderBenchOptions unknown;
  unknown.mesh_arm = "puma560";
  EXPECT_EQ(run_bench_render(unknown, out, err), 2);
  EXPECT_EQ(err.str(), "telear bench render: --mesh-arm must be ur6 or arm7, got 'puma560'\n");
  err.str("");
  RenderBenchOptions bad_detail;
  bad_detail.seconds = 0.01;
  bad_detail.width = 16;
  bad_detail.height = 16;
  bad_detail.mesh_arm = "arm7";
  bad_detail.mesh_detail = 2;
  EXPECT_EQ(run_bench_render(bad_detail, out, err), 1);
  EXPECT_THAT(err.str(), HasSubstr("telear bench render: --mesh-arm: /usr/bin/python3 "));
  EXPECT_THAT(err.str(), HasSubstr("failed: generate_arms.py: --detail must be in 6..256, got 2"));
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
