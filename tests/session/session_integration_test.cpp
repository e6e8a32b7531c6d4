// The Session against the embedded simulated servers (real gRPC on loopback): plan, validate,
// execute, monitor, AR / VR by measured delay (issue 6's tests).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <thread>

#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/session/session.hpp"
#include "telear/sim/stereo_rig.hpp"

namespace telear::session {
namespace {

using namespace std::chrono_literals;

class SessionIntegrationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto m = core::load_robot("puma560");
    ASSERT_TRUE(m) << m.error().message;
    model = *m;
    lab::EmbeddedServersOptions options;
    options.fps = 15.0;
    auto s = lab::EmbeddedServers::create(model, options);
    ASSERT_TRUE(s) << s.error().message;
    servers = std::move(*s);
    SessionOptions session_options;
    session_options.robot.address = servers->robot_address();
    session_options.robot.token = servers->token();
    session_options.robot.client_name = "session-test";
    session_options.vision.address = servers->vision_address();
    session_options.vision.token = servers->token();
    session_options.vision.width = 320;
    session_options.vision.height = 240;
    // Generous thresholds: the tests share 2 cores with llvmpipe rendering the simulated
    // cameras, so a "fresh" frame may be a few hundred ms old under load.
    session_options.display.late_threshold_s = 1.0;
    session_options.display.stream_timeout_s = 2.0;
    auto created = Session::create(model, session_options);
    ASSERT_TRUE(created) << created.error().message;
    session = std::move(*created);
    session->connect();
    ASSERT_TRUE(run_until([&] { return session->view().real && session->view().frame; }, 30.0))
        << "no state or frame from the embedded servers";
  }

  void TearDown() override {
    session.reset();
    servers.reset();
  }

  // Updates the session at ~50 Hz until `done` or the timeout (s); returns whether done.
  bool run_until(const std::function<bool()>& done, double timeout_s) {
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
           timeout_s) {
      session->update(0.02);
      if (done()) return true;
      std::this_thread::sleep_for(20ms);
    }
    return false;
  }

  Eigen::VectorXd real_q() const { return session->view().real->state.q; }

  // A 3-waypoint plan from the real robot's pose: joint 1 out and back.
  void build_plan(double joint1_delta) {
    ASSERT_TRUE(session->ghost_to_real().ok());
    ASSERT_TRUE(session->add_ghost_waypoint(0.0, "start").ok());
    ASSERT_TRUE(session->move_ghost(core::JointIncrement{0, joint1_delta}).accepted);
    ASSERT_TRUE(session->move_ghost(core::JointIncrement{2, -0.2}).accepted);
    ASSERT_TRUE(session->add_ghost_waypoint(0.0, "out").ok());
    ASSERT_TRUE(session->move_ghost(core::JointIncrement{0, -joint1_delta / 2}).accepted);
    ASSERT_TRUE(session->add_ghost_waypoint(0.0, "back").ok());
  }

  core::RobotModelPtr model;
  std::unique_ptr<lab::EmbeddedServers> servers;
  std::unique_ptr<Session> session;
};

TEST_F(SessionIntegrationTest, APlanExecutesOnTheRobotAndTheMonitorTracksIt) {
  ASSERT_TRUE(session->take_control().ok());
  build_plan(0.4);
  const Eigen::VectorXd goal = session->plan().waypoints().back().q;
  const ValidationReport report = session->validate_plan();
  ASSERT_TRUE(report.ok()) << report.summary();
  ASSERT_TRUE(session->start_preview().ok());
  const std::string previewed = session->previewed_hash();
  EXPECT_EQ(previewed.size(), 64u);
  const std::uint64_t bytes_before = session->stats().command_bytes_sent;
  auto ack = session->execute_plan();
  ASSERT_TRUE(ack) << ack.error().message;
  EXPECT_TRUE(session->executing());
  // The plan is the message: the server timed the same waypoints to the same trajectory as
  // the preview (equal hashes), and the message is a few hundred bytes, not 100 Hz samples.
  EXPECT_EQ(ack->plan_hash, previewed);
  EXPECT_EQ(session->executed_hash(), previewed);
  EXPECT_LT(session->stats().command_bytes_sent - bytes_before, 1000u);
  // Issue 23: the arm as reported at each frame's capture is the arm the frame shows (the
  // simulated rig sends the configuration it drew), while the arm moves.
  // Each frame's arm against the arm at its capture, and (the baseline, in the same run) against
  // the newest state the view holds.
  std::vector<double> errors_rad, newest_rad;
  std::uint64_t last_frame = 0;
  auto compare_capture_arm = [&] {
    const SessionView& v = session->view();
    if (!v.frame || v.frame->frame_id == last_frame || !v.capture_arm || !v.real) return;
    last_frame = v.frame->frame_id;
    if (v.frame->scene_q.size() != 6) return;
    errors_rad.push_back((v.capture_arm->q - v.frame->scene_q).cwiseAbs().maxCoeff());
    newest_rad.push_back((v.real->state.q - v.frame->scene_q).cwiseAbs().maxCoeff());
  };
  ASSERT_TRUE(run_until(
      [&] {
        compare_capture_arm();
        return !session->executing();
      },
      ack->duration_s + 15.0));
  ASSERT_GT(errors_rad.size(), 5u);
  // The rig's frame shows its robot's state at scene_state_ns (up to a state period before the
  // capture); the session's reports of the same robot at 100 Hz, interpolated, on two
  // clock-offset estimates: ~1 mrad (~1 mm at the tool) on a quiet machine. A loaded CI machine
  // delays states and pings by milliseconds (a run's median 3.2 mrad), so the typical frame is
  // held against the newest state measured in the same run (the frame's age of motion: tens of
  // mrad at this fast plan's speed) -- at most a third of it -- and to 5 mrad at most.
  std::sort(errors_rad.begin(), errors_rad.end());
  std::sort(newest_rad.begin(), newest_rad.end());
  const double median = errors_rad[errors_rad.size() / 2];
  std::printf(
      "the arm at capture vs the frame's: median %.2f mrad, worst %.2f; the newest state: "
      "median %.2f mrad (%zu frames)\n",
      1e3 * median, 1e3 * errors_rad.back(), 1e3 * newest_rad[newest_rad.size() / 2],
      errors_rad.size());
  EXPECT_LT(median, newest_rad[newest_rad.size() / 2] / 3.0);
  EXPECT_LT(median, 5e-3);
  EXPECT_EQ(session->last_execution_result(), "completed");
  ASSERT_NE(session->monitor(), nullptr);
  EXPECT_GT(session->monitor()->status().samples, 10);
  EXPECT_LT(session->monitor()->status().max_error_so_far, session->monitor()->options().tolerance);
  // The robot's own servo command followed the previewed trajectory (the server's 100 Hz
  // sampling of it, interpolated: micro-radians).
  EXPECT_GT(session->monitor()->status().command_samples, 10);
  EXPECT_LT(session->monitor()->status().max_command_deviation, 1e-3);
  ASSERT_TRUE(run_until([&] { return (real_q() - goal).cwiseAbs().maxCoeff() < 1e-3; }, 5.0))
      << "the real robot did not reach the plan's end";
}

TEST_F(SessionIntegrationTest, ACartesianPlanIsExecutedAsPreviewed) {
  // Out along a straight line of the tool and back along it (docs/trajectory.md, "Cartesian
  // segments"): the server expands the lines itself and gets the preview's hash.
  ASSERT_TRUE(session->take_control().ok());
  // From a pose away from the singularities (the embedded arm starts stretched).
  Eigen::VectorXd start(6);
  start << 0.17, -0.70, 0.52, 0.26, 0.79, -0.35;
  ASSERT_TRUE(session->initialize_real(start));
  ASSERT_TRUE(run_until([&] { return (real_q() - start).cwiseAbs().maxCoeff() < 1e-6; }, 15.0));
  ASSERT_TRUE(run_until([&] { return !session->executing(); }, 5.0));
  ASSERT_TRUE(session->ghost_to_real().ok());
  Eigen::Isometry3d T = core::tool_pose(*model, start);
  T.translation() += Eigen::Vector3d(0.06, 0.04, -0.05);
  auto out = core::solve_ik_nearest(*model, T, start);
  ASSERT_TRUE(out) << out.error().message;
  PlanWaypoint line_out(out->q, 0.0, std::nullopt, "out");
  line_out.cartesian = true;
  PlanWaypoint line_back(start, 0.0, std::nullopt, "back");
  line_back.cartesian = true;
  ASSERT_TRUE(session->plan().add({start, 0.0, std::nullopt, "start"}).ok());
  ASSERT_TRUE(session->plan().add(line_out).ok());
  ASSERT_TRUE(session->plan().add(line_back).ok());
  const ValidationReport report = session->validate_plan();
  ASSERT_TRUE(report.ok()) << report.summary();
  ASSERT_TRUE(session->start_preview().ok());
  const std::string previewed = session->previewed_hash();
  auto ack = session->execute_plan();
  ASSERT_TRUE(ack) << ack.error().message;
  EXPECT_EQ(ack->plan_hash, previewed);
  ASSERT_TRUE(run_until([&] { return !session->executing(); }, ack->duration_s + 15.0));
  EXPECT_EQ(session->last_execution_result(), "completed");
  ASSERT_NE(session->monitor(), nullptr);
  // The robot's servo command followed the previewed (expanded) trajectory.
  EXPECT_GT(session->monitor()->status().command_samples, 10);
  EXPECT_LT(session->monitor()->status().max_command_deviation, 1e-3);
}

TEST_F(SessionIntegrationTest, ValidationRejectsAPlanThatStartsFarFromTheRealRobot) {
  ASSERT_TRUE(session->take_control().ok());
  const Eigen::VectorXd before = real_q();
  ASSERT_TRUE(session->ghost_to_real().ok());
  ASSERT_TRUE(session->move_ghost(core::JointIncrement{1, 0.12}).accepted);
  ASSERT_TRUE(session->add_ghost_waypoint(0.0, "elsewhere").ok());
  ASSERT_TRUE(session->move_ghost(core::JointIncrement{0, 0.2}).accepted);
  ASSERT_TRUE(session->add_ghost_waypoint(0.0, "further").ok());
  const ValidationReport report = session->validate_plan();
  EXPECT_FALSE(report.ok());
  EXPECT_NE(
      report.summary().find("the plan starts 0.120 rad (6.9 deg) from the real robot at joint 2"),
      std::string::npos)
      << report.summary();
  auto ack = session->execute_plan();
  ASSERT_FALSE(ack);
  EXPECT_NE(ack.error().message.find("the plan is not valid"), std::string::npos);
  // Nothing moved.
  std::this_thread::sleep_for(200ms);
  session->update(0.02);
  EXPECT_LT((real_q() - before).cwiseAbs().maxCoeff(), 1e-9);
}

TEST_F(SessionIntegrationTest, TheMonitorCancelsWhenTheRobotDeviatesFromThePlan) {
  ASSERT_TRUE(session->take_control().ok());
  build_plan(0.8);
  auto ack = session->execute_plan();
  ASSERT_TRUE(ack) << ack.error().message;
  // Joint 1 sticks: the robot reports it where it was while the plan moves on.
  ASSERT_TRUE(servers->driver()
                  .robot()
                  .inject_fault({.joint = 0, .kind = sim::JointFaultKind::kStuck})
                  .ok());
  ASSERT_TRUE(run_until([&] { return !session->executing(); }, ack->duration_s + 15.0));
  const std::string& result = session->last_execution_result();
  EXPECT_EQ(result.rfind("cancelled: ", 0), 0u) << result;
  EXPECT_NE(result.find("joint 1 (waist)"), std::string::npos) << result;
  EXPECT_NE(result.find("beyond the tolerance"), std::string::npos) << result;
  EXPECT_TRUE(session->monitor()->cancelled());
}

TEST_F(SessionIntegrationTest, InjectedVideoDelaySwitchesArToVrAndBack) {
  ASSERT_TRUE(run_until([&] { return session->view().display.mode == DisplayMode::kAR; }, 20.0))
      << session->view().display.reason;
  const int ar_to_vr = session->display().ar_to_vr_switches();
  session->set_injected_video_delay(2.5);
  ASSERT_TRUE(run_until([&] { return session->view().display.mode == DisplayMode::kVR; }, 10.0));
  EXPECT_EQ(session->display().ar_to_vr_switches(), ar_to_vr + 1);
  EXPECT_TRUE(session->view().display.frame_stale);
  session->set_injected_video_delay(0.0);
  ASSERT_TRUE(run_until([&] { return session->view().display.mode == DisplayMode::kAR; }, 20.0));
  EXPECT_FALSE(session->view().display.frame_stale);
}

TEST_F(SessionIntegrationTest, AStoppedVideoStreamIsShownAsStaleInVr) {
  ASSERT_TRUE(run_until([&] { return session->view().display.mode == DisplayMode::kAR; }, 20.0));
  servers->vision_server().stop();
  ASSERT_TRUE(run_until([&] { return session->view().display.stream_stopped; }, 10.0));
  EXPECT_EQ(session->view().display.mode, DisplayMode::kVR);
  EXPECT_TRUE(session->view().display.frame_stale);
  ASSERT_NE(session->view().frame, nullptr) << "the last frame is kept (marked stale)";
}

}  // namespace
}  // namespace telear::session
