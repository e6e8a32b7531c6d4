// The manual capture for registration (issue 15) through the embedded simulated servers (real
// gRPC, rendered frames): the arm is brought to each pose the way an operator would (a jog, a
// plan message), CaptureSession adds the pose at rest, reports the marker per eye, grows the
// coverage and the folder, and solves; the answer is compared with the simulated rig's truth.
#include "telear/session/capture_session.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

#include "capture_test_rig.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/session/registration_capture.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "telear/vision/registered_camera_file.hpp"
#include "telear/vision/registration.hpp"
#include "test_util/mesh_test_files.hpp"

namespace telear::session {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

class CaptureSessionTest : public test::CaptureRigTest {
 protected:
  void SetUp() override {
    test::CaptureRigTest::SetUp();
    if (HasFatalFailure()) return;
    // Where the operator jogged the arm first: both cameras see the marker.
    auto visible = test::marker_visible_start();
    ASSERT_TRUE(visible) << visible.error().message;
    start = *visible;
    lab::EmbeddedServersOptions options;
    options.calibration_file = calibration;
    options.initial_q = start;
    options.fps = 10.0;
    options.supersample = 2;
    auto s = lab::EmbeddedServers::create(model, options);
    ASSERT_TRUE(s) << s.error().message;
    servers = std::move(*s);
    net::RobotClientOptions robot_options;
    robot_options.address = servers->robot_address();
    robot_options.token = servers->token();
    robot_options.client_name = "capture-session-test";
    robot = std::make_unique<net::RobotClient>(robot_options);
    robot->start();
    vision = start_vision(0, 0);
    // A long heartbeat: the servers, the renderer and the solver share a loaded machine.
    ASSERT_TRUE(robot->acquire_lease(1.0));
  }

  std::unique_ptr<net::VisionClient> start_vision(int width, int height) {
    net::VisionClientOptions vision_options;
    vision_options.address = servers->vision_address();
    vision_options.token = servers->token();
    vision_options.client_name = "capture-session-test";
    vision_options.jpeg_quality = 100;
    vision_options.width = width;
    vision_options.height = height;
    auto client = std::make_unique<net::VisionClient>(vision_options);
    client->start();
    return client;
  }

  void TearDown() override {
    vision.reset();
    robot.reset();
    servers.reset();
  }

  // What the operator's "move there" does: a plan of two waypoints (the capture does not care
  // how the arm got to a pose; add_current_pose waits until it is at rest).
  void send_to(const Eigen::VectorXd& target, const std::string& id) {
    auto state = robot->wait_state(0, 5.0);
    ASSERT_TRUE(state);
    core::TrajectoryOptions timing;
    auto trajectory = core::Trajectory::create(*model, {{state->state.q}, {target}}, timing);
    ASSERT_TRUE(trajectory) << trajectory.error().message;
    auto ack = robot->execute_plan(id, *trajectory);
    if (!ack && ack.error().message.find("lease lapsed") != std::string::npos) {
      // A starved heartbeat on a loaded test machine, not what is tested: take it again.
      ASSERT_TRUE(robot->acquire_lease(1.0));
      ack = robot->execute_plan(id + "-again", *trajectory);
    }
    ASSERT_TRUE(ack) << ack.error().message;
  }

  CaptureSessionOptions options_for(const std::string& name) {
    CaptureSessionOptions options;
    options.directory = (dir / name).string();
    options.frames_per_pose = 2;
    options.settle_s = 0.1;
    return options;
  }

  Eigen::VectorXd start;
  std::unique_ptr<lab::EmbeddedServers> servers;
  std::unique_ptr<net::RobotClient> robot;
  std::unique_ptr<net::VisionClient> vision;
};

TEST_F(CaptureSessionTest, JoggedPosesAreAddedAtRestAndSolvedAgainstTheTruth) {
  auto opened = CaptureSession::open(*model, *robot, *vision, options_for("manual"));
  ASSERT_TRUE(opened) << opened.error().message;
  CaptureSession& capture = **opened;
  EXPECT_EQ(capture.marker().id, marker.id);  // the robot's own marker by default
  // The calibration is written at once, the manifest with the first pose.
  EXPECT_TRUE(fs::exists(fs::path(capture.directory()) / "cameras.yaml"));
  EXPECT_FALSE(fs::exists(fs::path(capture.directory()) / "capture.yaml"));

  // Pose 0: where the operator left the arm.
  auto first = capture.add_current_pose();
  ASSERT_TRUE(first) << first.error().message;
  EXPECT_EQ(first->index, 0);
  EXPECT_EQ(first->frames, 2);
  EXPECT_TRUE(first->left_seen && first->right_seen) << first->summary();
  EXPECT_EQ(first->summary(), "pose 0: 2 frames, marker seen left and right");
  EXPECT_LT((first->q - start).cwiseAbs().maxCoeff(), 0.01);

  // Pose 1: after a jog of the last joint by 8 degrees (the console's and the CLI's jog),
  // added the console's way: on the worker, appended by poll_add once the arm is at rest.
  auto jog = robot->jog(core::JointIncrement{5, core::radians_from_degrees(8.0)}, 0.5);
  ASSERT_TRUE(jog) << jog.error().message;
  ASSERT_TRUE(capture.start_add_pose().ok());
  EXPECT_TRUE(capture.adding());
  Status again = capture.start_add_pose();
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.error().message,
            "pose 1 is being added (waiting for the arm to come to rest): wait for it");
  auto blocked = capture.add_current_pose();
  ASSERT_FALSE(blocked);
  EXPECT_EQ(blocked.error().message, "a pose is being added: wait for it");
  std::optional<Result<CapturedPoseReport>> second;
  for (int poll = 0; poll < 6000 && !second; ++poll) {
    second = capture.poll_add();
    if (!second) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(second.has_value()) << "the add did not finish in 60 s";
  ASSERT_TRUE(*second) << second->error().message;
  EXPECT_FALSE(capture.adding());
  EXPECT_FALSE(capture.poll_add().has_value());  // the outcome is given once
  EXPECT_EQ(capture.adds_finished(), 1);
  EXPECT_EQ(capture.last_add_error(), "");
  EXPECT_EQ((*second)->index, 1);
  EXPECT_NEAR((*second)->q[5] - first->q[5], core::radians_from_degrees(8.0), 0.01);

  // Too few poses to solve: refused, saying so, and kept for the panel.
  auto early = capture.solve();
  ASSERT_FALSE(early);
  EXPECT_EQ(capture.last_solve_error(), early.error().message);
  EXPECT_FALSE(capture.solution());

  // The folder is complete after every pose, in capture_for_registration's format.
  auto folder = vision::load_capture_folder(capture.directory());
  ASSERT_TRUE(folder) << folder.error().message;
  ASSERT_EQ(folder->poses.size(), 2u);
  EXPECT_EQ(folder->camera_file, "cameras.yaml");
  EXPECT_EQ(folder->robot, "puma560");
  EXPECT_EQ(folder->poses[1].frames[1].right_image, "pose_001/right_1.png");

  // More poses, spread as the automatic chooser would (the operator's judgement here; the
  // chooser ignores the arm hiding the marker, so some may not see it: reported, kept).
  const std::vector<Eigen::VectorXd> poses =
      choose_capture_poses(*model, start, rig.cameras, marker, 12, 3);
  ASSERT_GE(poses.size(), 10u);
  int revision = capture.revision();
  for (std::size_t p = 0; p < poses.size(); ++p) {
    send_to(poses[p], "manual-" + std::to_string(p));
    auto added = capture.add_current_pose();  // waits while the arm moves
    ASSERT_TRUE(added) << added.error().message;
    std::printf("%s\n", added->summary().c_str());
    EXPECT_LT((added->q - poses[p]).cwiseAbs().maxCoeff(), 0.01) << "added before it arrived";
    EXPECT_GT(capture.revision(), revision);
    revision = capture.revision();
  }
  const int count = static_cast<int>(poses.size()) + 2;
  ASSERT_EQ(static_cast<int>(capture.poses().size()), count);
  EXPECT_GE(capture.detected().left_found, 8);
  EXPECT_GE(capture.detected().right_found, 8);
  int both = 0, seen = 0;
  for (const CapturedPoseReport& pose : capture.poses()) {
    both += pose.left_seen && pose.right_seen;
    seen += pose.left_seen || pose.right_seen;
    if (!pose.left_seen) {
      EXPECT_THAT(pose.notes, ::testing::Contains("pose " + std::to_string(pose.index) +
                                                  ": the marker was not found in the left eye"));
    }
  }
  EXPECT_GE(both, 8);
  EXPECT_EQ(capture.detected().observations.views.back().name, "pose " + std::to_string(count - 1));

  // The coverage so far: green where the marker was found, dark elsewhere.
  const cv::Mat coverage = capture.coverage();
  ASSERT_EQ(coverage.cols, 2 * rig.cameras.left.width);
  ASSERT_EQ(coverage.rows, rig.cameras.left.height);
  int green = 0;
  for (int y = 0; y < coverage.rows; ++y) {
    for (int x = 0; x < coverage.cols; ++x) {
      const cv::Vec3b bgr = coverage.at<cv::Vec3b>(y, x);
      green += bgr[1] > bgr[0] + 40 && bgr[1] > bgr[2] + 40;
    }
  }
  EXPECT_GT(green, 8 * 200) << "the markers' quadrilaterals are not filled";
  EXPECT_EQ(coverage.at<cv::Vec3b>(coverage.rows - 1, 5), cv::Vec3b(40, 40, 40));

  auto solved = capture.solve();
  ASSERT_TRUE(solved) << solved.error().message;
  ASSERT_TRUE(capture.solution());
  EXPECT_TRUE(capture.last_solve_error().empty());
  const vision::HandEyeResult& result = solved->result;
  const auto left = vision::registration_error(rig.cameras.left.T_cam_base, result.T_left_base);
  const auto right = vision::registration_error(rig.cameras.right.T_cam_base, result.T_right_base);
  std::printf(
      "manual capture of %d poses: registration left %.3f mm %.4f deg, right %.3f mm %.4f deg; "
      "sigma %.3f mm %.4f deg\n",
      count, left.position_mm, left.rotation_deg, right.position_mm, right.rotation_deg,
      result.base_sigma.position_mm, result.base_sigma.rotation_deg);
  EXPECT_LT(left.position_mm, 2.0);
  EXPECT_LT(right.position_mm, 2.0);
  EXPECT_LT(left.rotation_deg, 0.2);
  EXPECT_EQ(static_cast<int>(result.views.size()), seen);  // the poses with the marker
  EXPECT_THAT(vision::capture_registration_report(*solved), HasSubstr("uncertainty (1 sigma)"));
}

TEST_F(CaptureSessionTest, RefusesAUsedFolderBadOptionsAndAReducedStream) {
  CaptureSessionOptions options = options_for("used");
  fs::create_directories(options.directory);
  { std::ofstream(fs::path(options.directory) / "capture.yaml") << "telear_capture: 1\n"; }
  auto opened = CaptureSession::open(*model, *robot, *vision, options);
  ASSERT_FALSE(opened);
  EXPECT_THAT(opened.error().message, HasSubstr("already holds a capture (capture.yaml)"));

  options = options_for("bad");
  options.frames_per_pose = 0;
  opened = CaptureSession::open(*model, *robot, *vision, options);
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().message, "capture: frames_per_pose 0 must be 1..30");

  // A stream reduced for display would not match the calibration: refused, nothing recorded.
  auto reduced = start_vision(320, 240);
  opened = CaptureSession::open(*model, *robot, *reduced, options_for("reduced"));
  ASSERT_TRUE(opened) << opened.error().message;
  auto added = (*opened)->add_current_pose();
  ASSERT_FALSE(added);
  const std::string reduced_error =
      "pose 0: the stream's images are 320x240, the calibration's 640x480: capture at the "
      "cameras' own size";
  EXPECT_EQ(added.error().message, reduced_error);
  // The same on the worker: the error is kept for the panel.
  ASSERT_TRUE((*opened)->start_add_pose().ok());
  std::optional<Result<CapturedPoseReport>> later;
  for (int poll = 0; poll < 6000 && !later; ++poll) {
    later = (*opened)->poll_add();
    if (!later) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(later.has_value());
  ASSERT_FALSE(*later);
  EXPECT_EQ(later->error().message, reduced_error);
  EXPECT_EQ((*opened)->last_add_error(), reduced_error);
  EXPECT_TRUE((*opened)->poses().empty());
  EXPECT_FALSE(fs::exists(fs::path((*opened)->directory()) / "capture.yaml"));

  // Another target than the robot's marker: detected in every pose and named in the folder.
  // This rig's flange carries the marker, so the board is not seen, and the pose says so.
  options = options_for("board");
  auto board = vision::parse_registration_target("charuco:4x4:0.08:0.05:4x4_50");
  ASSERT_TRUE(board) << board.error().message;
  options.target = *board;
  opened = CaptureSession::open(*model, *robot, *vision, options);
  ASSERT_TRUE(opened) << opened.error().message;
  EXPECT_EQ((*opened)->target().spec(), "charuco:4x4:0.08:0.05:DICT_4X4_50");
  added = (*opened)->add_current_pose();
  ASSERT_TRUE(added) << added.error().message;
  EXPECT_EQ(added->summary(), "pose 0: 2 frames, board not seen");
  EXPECT_THAT(added->notes, ::testing::Contains(HasSubstr("the board")));
  auto folder = vision::load_capture_folder((*opened)->directory());
  ASSERT_TRUE(folder) << folder.error().message;
  EXPECT_EQ(folder->target, "charuco:4x4:0.08:0.05:DICT_4X4_50");
}

}  // namespace
}  // namespace telear::session
