// Registration from images captured through the servers (issue 15): the embedded simulated
// robot and stereo vision servers on loopback, real gRPC; capture_for_registration moves the
// PUMA 560 through automatic poses, writes a capture folder, and the hand-eye registration
// solved from the detected marker corners is compared with the simulated rig's true cameras.
#include "telear/session/registration_capture.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "capture_test_rig.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/workspace.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/session/marker_visibility.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/sim/rig_robot.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/capture_observations.hpp"
#include "telear/vision/hand_eye_registration.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "telear/vision/registered_camera_file.hpp"
#include "test_util/mesh_test_files.hpp"

namespace telear::session {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

class RegistrationCaptureTest : public test::CaptureRigTest {
 protected:
  void SetUp() override {
    test::CaptureRigTest::SetUp();
    if (HasFatalFailure()) return;
    // Start where both cameras detect the marker (the operator's jog before capturing): the
    // first configuration the simulated rig's own observations found it at in both eyes.
    auto visible = test::marker_visible_start();
    ASSERT_TRUE(visible) << visible.error().message;
    Eigen::VectorXd start = *visible;
    lab::EmbeddedServersOptions options;
    options.calibration_file = calibration;
    options.initial_q = start;
    options.fps = 10.0;
    // 4 x 4 samples per pixel: edges integrated over the pixel's area as a real sensor does
    // (at 2 x 2 the corners' residual doubles, docs/registration.md).
    options.supersample = 4;
    auto s = lab::EmbeddedServers::create(model, options);
    ASSERT_TRUE(s) << s.error().message;
    servers = std::move(*s);
    net::RobotClientOptions robot_options;
    robot_options.address = servers->robot_address();
    robot_options.token = servers->token();
    robot_options.client_name = "capture-test";
    robot = std::make_unique<net::RobotClient>(robot_options);
    robot->start();
    net::VisionClientOptions vision_options;
    vision_options.address = servers->vision_address();
    vision_options.token = servers->token();
    vision_options.client_name = "capture-test";
    vision_options.jpeg_quality = 100;
    vision = std::make_unique<net::VisionClient>(vision_options);
    vision->start();
  }

  void TearDown() override {
    vision.reset();
    robot.reset();
    servers.reset();
  }

  std::unique_ptr<lab::EmbeddedServers> servers;
  std::unique_ptr<net::RobotClient> robot;
  std::unique_ptr<net::VisionClient> vision;
};

TEST_F(RegistrationCaptureTest, CapturesThroughTheServersAndRegistersAgainstTheTruth) {
  RegistrationCaptureOptions options;
  options.directory = (dir / "capture").string();
  options.auto_poses = 24;
  options.frames_per_pose = 2;
  // Another seed (other automatic poses): TELEAR_CAPTURE_TEST_SEED=N (docs/registration.md).
  if (const char* seed = std::getenv("TELEAR_CAPTURE_TEST_SEED")) options.seed = std::stoull(seed);
  // The operator's copy of the table and box: the poses keep the marker's sight lines clear
  // of them as of the arm's own body.
  auto workspace = core::load_workspace_file(core::default_workspace_file("puma560"));
  ASSERT_TRUE(workspace) << workspace.error().message;
  options.workspace = *workspace;
  options.velocity_scale = 1.0;
  options.settle_s = 0.1;
  options.marker = marker;
  // The lease taken here with a 1 s heartbeat (capture_for_registration keeps a lease it finds
  // held): the 2-core test machine also renders both cameras and may starve the heartbeat
  // thread for longer than the server's default 250 ms (the Session asks for the same).
  ASSERT_TRUE(robot->acquire_lease(1.0));
  std::vector<std::string> progress;
  auto captured =
      capture_for_registration(*model, *robot, *vision, options, [&](const CaptureProgress& p) {
        std::printf("%s\n", p.message.c_str());
        progress.push_back(p.message);
      });
  ASSERT_TRUE(captured) << captured.error().message;
  for (const auto& note : captured->notes) std::printf("note: %s\n", note.c_str());
  ASSERT_GE(captured->capture.poses.size(), 10u);
  ASSERT_FALSE(progress.empty());
  EXPECT_THAT(progress.front(), HasSubstr("pose 1/"));

  // The folder reads back with every image, and the camera file beside it.
  auto folder = vision::load_capture_folder(options.directory);
  ASSERT_TRUE(folder) << folder.error().message;
  EXPECT_EQ(folder->poses.size(), captured->capture.poses.size());
  EXPECT_EQ(folder->camera_file, "cameras.yaml");
  EXPECT_EQ(folder->poses.front().frames.size(), static_cast<std::size_t>(options.frames_per_pose));

  auto detected = vision::detect_capture_targets(options.directory, *folder, marker);
  ASSERT_TRUE(detected) << detected.error().message;
  for (const auto& note : detected->notes) std::printf("detection: %s\n", note.c_str());
  // Every pose kept shows the marker in both eyes: the capture replaced those that did not.
  EXPECT_EQ(detected->left_found, static_cast<int>(folder->poses.size()));
  EXPECT_EQ(detected->right_found, static_cast<int>(folder->poses.size()));
  // The coverage image marks where each eye found the marker and leaves the rest dark.
  const cv::Mat coverage =
      vision::coverage_image(*detected, rig.cameras.left.width, rig.cameras.left.height);
  ASSERT_EQ(coverage.cols, 2 * rig.cameras.left.width);
  for (const vision::HandEyeView& view : detected->observations.views) {
    if (view.right.size() != 4) continue;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const vision::TargetPixel& p : view.right) centre += p.pixel / 4.0;
    // Around the centre (another marker's white outline or number may cross the centre).
    bool green = false;
    for (const auto& [dx, dy] : {std::pair{0, 0}, {3, 0}, {-3, 0}, {0, 3}, {0, -3}}) {
      const cv::Vec3b inside =
          coverage.at<cv::Vec3b>(static_cast<int>(centre.y()) + dy,
                                 rig.cameras.left.width + static_cast<int>(centre.x()) + dx);
      green = green || inside[1] > inside[0] + 40;
    }
    EXPECT_TRUE(green) << view.name << ": no green where the marker was";
  }
  EXPECT_EQ(coverage.at<cv::Vec3b>(coverage.rows - 1, 5), cv::Vec3b(40, 40, 40));
  auto result = vision::register_hand_eye(
      *model, rig.cameras.left, rig.cameras.right,
      vision::right_from_left(rig.cameras.left.T_cam_base, rig.cameras.right.T_cam_base),
      detected->observations);
  ASSERT_TRUE(result) << result.error().message;
  for (const auto& note : result->notes) std::printf("registration: %s\n", note.c_str());
  const auto left = vision::registration_error(rig.cameras.left.T_cam_base, result->T_left_base);
  const auto right = vision::registration_error(rig.cameras.right.T_cam_base, result->T_right_base);
  const double target_mm =
      1000.0 *
      (result->T_flange_target.translation() - marker.T_flange_marker.translation()).norm();
  // OpenCV's closed form (Shah and Li) on the same captures, per eye.
  ASSERT_TRUE(result->baseline_left.solved);
  ASSERT_TRUE(result->baseline_right.solved);
  const auto shah_li_left =
      vision::registration_error(rig.cameras.left.T_cam_base, result->baseline_left.T_cam_base);
  const auto shah_li_right =
      vision::registration_error(rig.cameras.right.T_cam_base, result->baseline_right.T_cam_base);
  // The overlay: the arm's body drawn through the registered cameras against the true ones.
  auto body = core::body_description_for(*model);
  ASSERT_TRUE(body) << body.error().message;
  vision::StereoCameraModel registered = rig.cameras;
  registered.left.T_cam_base = result->T_left_base;
  registered.right.T_cam_base = result->T_right_base;
  vision::AccuracyOptions accuracy_options;
  accuracy_options.configurations = 20;
  const vision::AccuracyReport accuracy = vision::evaluate_accuracy(
      *model, core::build_arm_body(*body), rig.cameras, registered, accuracy_options);
  std::printf(
      "seed %llu: %zu poses captured, %d used; registration left %.3f mm %.4f deg, right %.3f mm "
      "%.4f deg (sigma %.3f mm %.4f deg); marker on the flange %.3f mm; residual RMS %.3f / %.3f "
      "px; overlay RMS %.4f / %.4f px; Shah-Li left %.3f mm %.4f deg, right %.3f mm %.4f deg "
      "(%.1fx / %.1fx the bundle adjustment's error)\n",
      static_cast<unsigned long long>(options.seed), folder->poses.size(), result->views_used,
      left.position_mm, left.rotation_deg, right.position_mm, right.rotation_deg,
      result->base_sigma.position_mm, result->base_sigma.rotation_deg, target_mm,
      result->left.rms_px, result->right.rms_px, accuracy.left.overlay.rms_px,
      accuracy.right.overlay.rms_px, shah_li_left.position_mm, shah_li_left.rotation_deg,
      shah_li_right.position_mm, shah_li_right.rotation_deg,
      shah_li_left.position_mm / left.position_mm, shah_li_right.position_mm / right.position_mm);
  // Issue 15's targets per eye (measured: 0.20-0.39 mm over seeds 1-5, docs/registration.md).
  // Views a few tenths of a pixel off (0.11-0.14 px against the median's 0.04 at seed 1) are
  // dropped since the outlier floor is 0.1 px (issue 26): at most a quarter of them.
  EXPECT_GE(result->views_used, 18);
  EXPECT_LE(left.position_mm, 0.5);
  EXPECT_LE(right.position_mm, 0.5);
  EXPECT_LE(left.rotation_deg, 0.05);
  EXPECT_LE(right.rotation_deg, 0.05);
  EXPECT_LE(accuracy.left.overlay.rms_px, 0.1);
  EXPECT_LE(accuracy.right.overlay.rms_px, 0.1);
  EXPECT_LT(target_mm, 1.0);
  // The bundle adjustment beats the closed form it starts from, in both eyes.
  EXPECT_LT(left.position_mm, shah_li_left.position_mm);
  EXPECT_LT(right.position_mm, shah_li_right.position_mm);
  EXPECT_LT(left.rotation_deg, shah_li_left.rotation_deg);
  EXPECT_LT(right.rotation_deg, shah_li_right.rotation_deg);
}

TEST_F(RegistrationCaptureTest, RefusesAFolderThatAlreadyHoldsACapture) {
  RegistrationCaptureOptions options;
  options.directory = (dir / "capture").string();
  options.poses = {sim::rest_configuration(*model)};
  options.marker = marker;
  fs::create_directories(options.directory);
  { std::ofstream(fs::path(options.directory) / "capture.yaml") << "telear_capture: 1\n"; }
  auto captured = capture_for_registration(*model, *robot, *vision, options);
  ASSERT_FALSE(captured);
  EXPECT_THAT(captured.error().message, HasSubstr("already holds a capture (capture.yaml)"));
  options.directory = (dir / "other").string();
  options.frames_per_pose = 0;
  captured = capture_for_registration(*model, *robot, *vision, options);
  ASSERT_FALSE(captured);
  EXPECT_EQ(captured.error().message, "capture: frames_per_pose 0 must be 1..30");
}

// The automatic poses' line-of-sight test: a marker facing the camera is seen until an object
// stands between them (named) or the wrist turns it away.
TEST(MarkerVisibilityTest, NamesWhatHidesTheMarker) {
  auto loaded = test::load_puma_capture_rig();
  ASSERT_TRUE(loaded) << loaded.error().message;
  const core::RobotModel& model = *loaded->model;
  const sim::StereoRig& rig = loaded->rig;
  const core::MarkerMount& marker = loaded->marker;
  sim::MarkerObservationsOptions find;
  find.rig_file = sim::default_rig_file("puma560");
  find.configurations = 4;
  find.seed = 2;
  auto found = sim::simulate_marker_observations(find);
  ASSERT_TRUE(found) << found.error().message;
  const vision::CameraModel& camera = rig.cameras.left;
  auto body = core::body_description_for(model);
  ASSERT_TRUE(body) << body.error().message;
  const core::ArmBody arm = core::build_arm_body(*body);
  MarkerVisibility clear(model, marker, &arm, nullptr);
  // A configuration where the rendered image showed the marker, and the test agrees.
  Eigen::VectorXd q;
  for (const auto& c : found->observations.configurations) {
    if (!c.left_pixels.empty() && clear.hidden_reason(camera, c.q).empty()) {
      q = c.q;
      break;
    }
  }
  ASSERT_GT(q.size(), 0) << "no detected configuration is predicted visible";
  // A 20 cm box halfway between the marker and the camera.
  core::Workspace workspace;
  core::WorkspaceObject blocker;
  blocker.name = "blocker";
  blocker.size_m = Eigen::Vector3d::Constant(0.2);
  const Eigen::Vector3d camera_centre = camera.T_cam_base.inverse().translation();
  blocker.T_base_object.translation() = 0.5 * (clear.marker_pose(q).translation() + camera_centre);
  workspace.objects.push_back(blocker);
  MarkerVisibility blocked(model, marker, &arm, &workspace);
  EXPECT_GE(blocked.occluder_count(), clear.occluder_count() + 1);
  EXPECT_EQ(blocked.hidden_reason(camera, q), "hidden by blocker");
  // The last joint turned half a turn: the marker's back faces the camera.
  Eigen::VectorXd turned = q;
  turned[5] += M_PI;
  EXPECT_THAT(clear.hidden_reason(camera, turned), ::testing::StartsWith("faces away ("));

  // Another target on the same mount: a board whose chessboard is the marker's size is seen
  // as the marker is; a 2 m board does not fit in the image.
  auto small_board = vision::parse_registration_target("charuco:2x2:0.05:0.048:4x4_50");
  ASSERT_TRUE(small_board) << small_board.error().message;
  auto large_board = vision::parse_registration_target("charuco:10x10:0.2:0.15:6x6_250");
  ASSERT_TRUE(large_board) << large_board.error().message;
  MarkerVisibility small(model, marker, &arm, nullptr, {}, *small_board);
  MarkerVisibility large(model, marker, &arm, nullptr, {}, *large_board);
  EXPECT_EQ(small.hidden_reason(camera, q), "");
  EXPECT_EQ(large.hidden_reason(camera, q), "outside the image");
  EXPECT_TRUE(small.marker_pose(q).isApprox(clear.marker_pose(q)));
}

// A big board's sight lines are at most a square apart: at this pose (the capture test's
// own automatic pose 4 for charuco:4x4:0.1:0.075 at seed 1) the shoulder hides the board's
// lower right in both eyes, between the 3 x 3 lines a marker gets. Seen anyway, the view kept
// 4 of 9 corners, 0.25-0.5 px off, and turned the registration from 0.21 to 1.85 mm.
TEST(MarkerVisibilityTest, ABoardHalfBehindTheShoulderIsHidden) {
  auto loaded = test::load_puma_capture_rig();
  ASSERT_TRUE(loaded) << loaded.error().message;
  const core::RobotModel& model = *loaded->model;
  const sim::StereoRig& rig = loaded->rig;
  auto body = core::body_description_for(model);
  ASSERT_TRUE(body) << body.error().message;
  const core::ArmBody arm = core::build_arm_body(*body);
  auto board = vision::parse_registration_target("charuco:4x4:0.1:0.075:4x4_50");
  ASSERT_TRUE(board) << board.error().message;
  MarkerVisibility visibility(model, loaded->marker, &arm, nullptr, {}, *board);
  Eigen::VectorXd q(6);
  q << -0.30470130403662427, -1.7352926246714422, 1.3677688899503175, -3.4953138739199106,
      -0.54780040714486533, 3.9601668865935191;
  EXPECT_EQ(visibility.hidden_reason(rig.cameras.left, q), "hidden by link1");
  EXPECT_EQ(visibility.hidden_reason(rig.cameras.right, q), "hidden by link1");
  // The marker at the same pose is clear of it (its 3 x 3 lines are unchanged).
  MarkerVisibility marker_only(model, loaded->marker, &arm, nullptr);
  EXPECT_EQ(marker_only.hidden_reason(rig.cameras.right, q), "");
}

// The spare poses a capture visits instead of one whose frames show the target too little:
// further candidates, none of them among the chosen, and the chosen the same as without them.
TEST(ChooseCapturePosesTest, SparesAreFurtherPosesNotAmongTheChosen) {
  auto loaded = test::load_puma_capture_rig();
  ASSERT_TRUE(loaded) << loaded.error().message;
  auto start = test::marker_visible_start();
  ASSERT_TRUE(start) << start.error().message;
  const std::vector<Eigen::VectorXd> alone =
      choose_capture_poses(*loaded->model, *start, loaded->rig.cameras, loaded->marker, 6, 4);
  std::vector<Eigen::VectorXd> spares;
  const std::vector<Eigen::VectorXd> chosen =
      choose_capture_poses(*loaded->model, *start, loaded->rig.cameras, loaded->marker, 6, 4,
                           nullptr, nullptr, std::nullopt, &spares);
  ASSERT_EQ(chosen.size(), 6u);
  ASSERT_EQ(alone.size(), chosen.size());
  for (std::size_t i = 0; i < chosen.size(); ++i) EXPECT_EQ(chosen[i], alone[i]) << "pose " << i;
  ASSERT_EQ(spares.size(), 6u);
  for (const Eigen::VectorXd& spare : spares) {
    for (const Eigen::VectorXd& pose : chosen) EXPECT_GT((spare - pose).norm(), 1e-6);
  }
}

}  // namespace
}  // namespace telear::session
