// The simulated capture modules (include/telear/sim/calibration_capture.hpp,
// marker_observations.hpp) at a small scale: the files they promise, the progress they
// report, and errors that name the option and the file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/sim/calibration_capture.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/camera_file.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::sim {
namespace {

namespace fs = std::filesystem;

TEST(CalibrationCapture, WritesEveryViewPerEyeAndTheTruth) {
  test_files::TempDir tmp("capture");
  const fs::path dir = tmp.file("capture");
  CalibrationCaptureOptions options;
  options.rig_file = test::data_path("rigs/puma560_rig.yaml");
  options.views = 3;
  options.supersample = 1;
  options.output_dir = dir.string();
  int calls = 0;
  auto capture = capture_calibration_views(
      options, [&](int view, int views, const std::string& left, const std::string& right) {
        ++calls;
        EXPECT_EQ(view, calls);
        EXPECT_EQ(views, 3);
        EXPECT_EQ(left, "left_0" + std::to_string(view - 1) + ".png");
        EXPECT_EQ(right, "right_0" + std::to_string(view - 1) + ".png");
      });
  ASSERT_TRUE(capture.ok()) << capture.error().message;
  EXPECT_EQ(calls, 3);
  ASSERT_EQ(capture->left_images.size(), 3u);
  ASSERT_EQ(capture->right_images.size(), 3u);
  for (const auto& path : capture->left_images) EXPECT_TRUE(fs::exists(path)) << path;
  for (const auto& path : capture->right_images) EXPECT_TRUE(fs::exists(path)) << path;
  // truth.yaml is a stereo camera file with both poses.
  auto truth = vision::load_camera_file(capture->truth_file);
  ASSERT_TRUE(truth.ok()) << truth.error().message;
  EXPECT_TRUE(truth->is_stereo());
  EXPECT_TRUE(truth->left_has_pose && truth->right_has_pose);
}

TEST(CalibrationCapture, BadOptionsAndRigsAreErrorsNamingThem) {
  CalibrationCaptureOptions options;
  options.rig_file = test::data_path("rigs/puma560_rig.yaml");
  test_files::TempDir tmp("capture_bad");
  options.output_dir = tmp.file("capture");
  options.views = 0;
  auto r = capture_calibration_views(options);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "views 0 is outside 1..100");
  options.views = 2;
  options.pattern = "chessboard:2x";
  r = capture_calibration_views(options);
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.error().message, ::testing::StartsWith("pattern: "));
  options.pattern = "chessboard:9x6:0.03";
  options.rig_file = "/nonexistent/rig.yaml";
  r = capture_calibration_views(options);
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.error().message, ::testing::HasSubstr("/nonexistent/rig.yaml"));
}

TEST(MarkerObservations, DetectsTheMarkerAtSeededConfigurations) {
  MarkerObservationsOptions options;
  options.rig_file = test::data_path("rigs/puma560_rig.yaml");
  options.configurations = 3;
  options.supersample = 2;
  int calls = 0;
  auto result = simulate_marker_observations(options, [&](int index, int count, bool, bool) {
    ++calls;
    EXPECT_EQ(index, calls);
    EXPECT_EQ(count, 3);
  });
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_EQ(calls, 3);
  const vision::RegistrationObservations& o = result->observations;
  EXPECT_EQ(o.robot, "puma560");
  EXPECT_EQ(o.point_in_flange.size(), 4u);
  EXPECT_EQ(static_cast<int>(o.configurations.size()) + result->skipped, 3);
  for (const auto& c : o.configurations) {
    EXPECT_EQ(c.q.size(), 6);
    EXPECT_TRUE(c.left_pixels.size() == 4u || c.right_pixels.size() == 4u);
  }
  // The same seed draws the same configurations.
  auto again = simulate_marker_observations(options);
  ASSERT_TRUE(again.ok());
  ASSERT_EQ(again->observations.configurations.size(), o.configurations.size());
  EXPECT_TRUE(again->observations.configurations[0].q.isApprox(o.configurations[0].q));
}

// Issue 26: the UR-type arm's +-360 deg joints put a random draw's arm through itself (seed 1's
// first configuration had the base in the upper arm), and the demo's capture started at that
// configuration, where the robot server refuses every move. With collision_free (the demo's
// pipeline asks for it) each one is free of contact, with itself and with the rig's scene.
TEST(MarkerObservations, EveryConfigurationIsFreeOfContact) {
  MarkerObservationsOptions options;
  options.rig_file = test::data_path("rigs/ur6_rig.yaml");
  options.robot = "ur6";
  options.configurations = 3;
  options.supersample = 1;
  options.seed = 1;  // the demo's
  options.collision_free = true;
  auto result = simulate_marker_observations(options);
  ASSERT_TRUE(result.ok()) << result.error().message;
  auto rig = load_stereo_rig(options.rig_file);
  ASSERT_TRUE(rig.ok());
  auto robot = geometry::load_robot_assets({"ur6", "", {}});
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  auto checker = geometry::make_collision_checker(robot->description, rig->workspace);
  ASSERT_TRUE(checker.ok()) << checker.error().message;
  ASSERT_FALSE(result->observations.configurations.empty());
  for (const auto& c : result->observations.configurations) {
    const geometry::CollisionReport report = checker->check(c.q);
    EXPECT_TRUE(report.collision_free())
        << report.contacts.front().body << " touches " << report.contacts.front().other;
  }
}

TEST(MarkerObservations, BadOptionsAndRigsAreErrorsNamingThem) {
  MarkerObservationsOptions options;
  options.rig_file = test::data_path("rigs/puma560_rig.yaml");
  options.configurations = 0;
  auto r = simulate_marker_observations(options);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "configurations 0 is outside 1..500");
  options.configurations = 1;
  options.rig_file = "/nonexistent/rig.yaml";
  r = simulate_marker_observations(options);
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.error().message, ::testing::StartsWith("rig_file: "));
  EXPECT_THAT(r.error().message, ::testing::HasSubstr("/nonexistent/rig.yaml"));
}

}  // namespace
}  // namespace telear::sim
