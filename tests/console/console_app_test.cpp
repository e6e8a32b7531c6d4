// The console headless (EGL frame buffer, no window, no X) against the embedded simulated
// servers, driven by a UI script exactly as `telear console --headless --script` runs it.

#include "telear/console/console_app.hpp"
#include "apps/console_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scripted_console.hpp"
#include "telear/console/console_actions.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/record/recording_series.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::console {
namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kWidth = 1280, kHeight = 800;

// Runs frames until `done` or the wall-clock budget; false on timeout or if the app quit.
template <typename Done>
bool run_until(ConsoleApp& app, double budget_s, Done done) {
  const auto start = Clock::now();
  while (!done()) {
    if (!app.frame()) return done();
    if (std::chrono::duration<double>(Clock::now() - start).count() > budget_s) return false;
  }
  return true;
}

struct Stats {
  double mean = 0, stddev = 0;
  int cyan = 0;  // pixels with the ghost's tint (blue-green high, red low)
};

Stats region_stats(const core::Image& image, int x0, int y0, int x1, int y1) {
  Stats s;
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const int r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
      const double l = 0.299 * r + 0.587 * g + 0.114 * b;
      sum += l;
      sum2 += l * l;
      ++n;
      if (b > 150 && g > 110 && r + 60 < b) ++s.cyan;
    }
  }
  s.mean = sum / n;
  s.stddev = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
  return s;
}

// The library checks its options by field (the command names its flags, tests/apps): the
// servers both or neither, local servers only when something can start them, the eye output.
TEST(ConsoleApp, OptionsAreRefusedNamingTheField) {
  std::ostringstream log;
  ConsoleOptions options;
  options.headless = true;
  auto created = ConsoleApp::create(options, log);
  ASSERT_FALSE(created);
  EXPECT_EQ(created.error().message,
            "no robot and vision server addresses, and no local servers to start");

  options.robot = "127.0.0.1:1";
  created = ConsoleApp::create(options, log);
  ASSERT_FALSE(created);
  EXPECT_EQ(created.error().message,
            "give both the robot and the vision server's address, or neither (local servers)");

  options = ConsoleOptions{};
  options.fullscreen_eyes = "three";
  created = ConsoleApp::create(options, log);
  ASSERT_FALSE(created);
  EXPECT_EQ(created.error().message, "fullscreen_eyes 'three': two-windows or sbs");
  options.fullscreen_eyes = "sbs";
  options.headless = true;
  created = ConsoleApp::create(options, log);
  ASSERT_FALSE(created);
  EXPECT_EQ(created.error().message,
            "fullscreen_eyes needs a display; it cannot be combined with headless");
}

TEST(ConsoleApp, ScriptedPlanExecutesScreenshotAndConnectionLoss) {
  test_files::TempDir tmp("console");
  const fs::path dir = tmp.path();
  const std::string shot = (dir / "console.png").string();
  fs::remove(shot);
  const std::string script = (dir / "plan.txt").string();
  std::ofstream(script) << "wait-until connected 30\n"
                           "wait-until in-control 10\n"
                           "wait-until ar 30   # a loaded machine may take seconds\n"
                           "ghost reset\n"
                           "plan add 0 start\n"
                           "ghost joint 2 +12deg\n"
                           "ghost joint 3 -10deg\n"
                           "plan add 0.5 middle\n"
                           "ghost cartesian base z -30mm\n"
                           "ghost gripper close\n"
                           "plan add 0.5 end\n"
                           "preview speed 4   # fails: no preview yet (counted, script goes on)\n"
                           "preview play\n"
                           "preview speed 4\n"
                           "wait-until preview-end 20\n"
                           "preview stop\n"
                           "ghost reset\n"
                           "validate\n"
                           "execute\n"
                           "wait-until idle 30\n"
                           "wait-until ar 30\n"
                           "screenshot " +
                               shot + "\n";
  // Kept running after the script (connection loss below).
  ConsoleOptions options = telear::test::scripted_headless_console(script, kWidth, kHeight);
  options.record = (dir / "console.mcap").string();  // issue 22: --record
  std::ostringstream log;
  auto created = ConsoleApp::create(options, log);
  ASSERT_TRUE(created) << created.error().message;
  ConsoleApp& app = **created;
  session::Session& session = app.session();

  ASSERT_TRUE(run_until(app, 45, [&] { return app.script().finished(); })) << log.str();
  EXPECT_EQ(app.script().failures(), 1) << log.str();  // the deliberate `preview speed` line
  EXPECT_THAT(log.str(), HasSubstr("line 12: preview speed 4"));

  // The real robot reached the plan's end.
  ASSERT_EQ(session.plan().size(), 3u);
  EXPECT_EQ(session.last_execution_result(), "completed");
  ASSERT_TRUE(session.view().real);
  const Eigen::VectorXd q_end = session.plan().waypoints().back().q;
  const Eigen::VectorXd q_real = session.view().real->state.q;
  EXPECT_LT((q_real - q_end).cwiseAbs().maxCoeff(), 0.01) << q_real.transpose() << "\n"
                                                          << q_end.transpose();
  EXPECT_NEAR(session.plan().waypoint(1).q[1] - session.plan().waypoint(0).q[1], 12 * M_PI / 180,
              1e-9);

  // The screenshot: the whole console, with the video and the arm in the view panel.
  ASSERT_TRUE(fs::exists(shot));
  const core::Image& image = app.last_image();
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  const Stats view = region_stats(image, 10, 80, static_cast<int>(kWidth * 0.69) - 10,
                                  static_cast<int>(kHeight * 0.58) - 10);
  EXPECT_GT(view.stddev, 20.0);  // a video, not a flat panel
  EXPECT_GT(view.cyan, 200);     // the ghost is drawn
  const Stats panels =
      region_stats(image, static_cast<int>(kWidth * 0.7), 80, kWidth - 5, kHeight - 40);
  EXPECT_GT(panels.stddev, 5.0);  // text and widgets
  // Glass to glass: this stream is scaled (320x240 of the rig's 640x480), so the frame code the
  // embedded servers stamp does not survive it: capture -> shown is "not measured: no frame
  // code" (docs/latency.md); ConsoleApp.MeasuresCaptureToShownFromTheFrameCode measures it.
  EXPECT_EQ(session.stats().shown.samples, 0);
  EXPECT_GT(session.stats().shown_without_code, 0);

  // The recording (--record): the session's states, its ghost, the video, its own events.
  auto recorded = app.stop_recording();
  ASSERT_TRUE(recorded) << recorded.error().message;
  EXPECT_GT(recorded->written["/robot/joint_states"], 50u);  // 50 Hz over the script
  EXPECT_GT(recorded->written["/ghost/joint_states"], 0u);
  // The session's own stream feeds it (no second stream to decode): frames and their latency.
  EXPECT_GT(recorded->written["/camera/left/image/compressed"], 10u);
  EXPECT_GT(recorded->written["/telear/latency"], 10u);
  EXPECT_GT(recorded->written["/events"], 5u);  // the lease, validation, execution ...
  EXPECT_EQ(recorded->bytes, fs::file_size(dir / "console.mcap"));
  EXPECT_THAT(log.str(), HasSubstr("telear console: recording to "));
  // The session's workflow as structured events, the executed plan with its hash; the ghost
  // the view drew at no less than the state stream's rate.
  auto series = record::load_recording_series((dir / "console.mcap").string());
  ASSERT_TRUE(series) << series.error().message;
  std::map<std::string, int> kinds;
  const record::PlanEventSample* executed = nullptr;
  for (const record::PlanEventSample& e : series->plan_events) {
    ++kinds[e.kind_name];
    if (e.kind_name == "EXECUTE" && !e.plan_hash.empty() && !executed) executed = &e;
  }
  EXPECT_GE(kinds["LEASE_ACQUIRED"], 1);
  EXPECT_GE(kinds["PREVIEW"], 2);  // started, stopped
  EXPECT_GE(kinds["VALIDATE"], 1);
  EXPECT_GE(kinds["DISPLAY_MODE"], 1);  // VR -> AR once the video arrives
  ASSERT_NE(executed, nullptr);
  EXPECT_EQ(executed->plan_hash, session.executed_hash());
  EXPECT_THAT(executed->plan_id, ::testing::StartsWith("plan-"));
  const double ghost_hz = series->ghost.samples.size() / series->duration_s();
  EXPECT_GE(ghost_hz, 30.0) << series->ghost.samples.size() << " in " << series->duration_s();

  // Connection loss: stop the servers; the console says so and keeps drawing.
  const std::string token = app.servers()->token();
  app.servers()->stop();
  ASSERT_TRUE(run_until(app, 10, [&] { return !session.robot_connected(); }));
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(app.frame());
  EXPECT_TRUE(session.connected());  // still trying: the panel shows "CONNECTION LOST"

  // Reconnection through the connection panel's path: new servers, Connect.
  auto model = core::load_robot("puma560");
  ASSERT_TRUE(model);
  auto servers = lab::EmbeddedServers::create(*model);
  ASSERT_TRUE(servers) << servers.error().message;
  UiState& ui = app.ui();
  std::snprintf(ui.robot_address, sizeof ui.robot_address, "%s",
                (*servers)->robot_address().c_str());
  std::snprintf(ui.vision_address, sizeof ui.vision_address, "%s",
                (*servers)->vision_address().c_str());
  std::snprintf(ui.token, sizeof ui.token, "%s", (*servers)->token().c_str());
  ASSERT_TRUE(apply_action(app.session(), ui, simple(ActionKind::kConnect)).ok());
  ASSERT_TRUE(run_until(app, 20, [&] {
    return app.session().robot_connected() && app.session().view().frame != nullptr &&
           app.session().in_control();
  }));
  app.session().disconnect();
}

// Glass to glass (docs/latency.md): at the rig's own size the frame code the embedded servers
// stamp reaches the AR view unscaled, and the console reads it back from the drawn eye.
TEST(ConsoleApp, MeasuresCaptureToShownFromTheFrameCode) {
  test_files::TempDir tmp("console_shown");
  const std::string script = (tmp.path() / "wait.txt").string();
  std::ofstream(script) << "wait-until connected 30\n";
  ConsoleOptions options = telear::test::scripted_headless_console(script, 960, 600);
  options.resolution = "640x480";  // the rig's own size: an unscaled stream
  std::ostringstream log;
  auto created = ConsoleApp::create(options, log);
  ASSERT_TRUE(created) << created.error().message;
  ConsoleApp& app = **created;
  ASSERT_TRUE(run_until(app, 20, [&] { return app.session().stats().shown.samples >= 3; }))
      << log.str();
  const session::SessionStats stats = app.session().stats();
  EXPECT_GT(stats.shown.p50_s, 0.0);
  EXPECT_LT(stats.shown.p50_s, 5.0);  // a capture time of this run, not a stray value
  EXPECT_EQ(stats.shown_without_code, 0);
  app.session().disconnect();
}

// Issue 12: `telear console --arm ur6`: the ghost is the URDF arm drawn from its meshes, the
// embedded servers simulate the same arm on its own rig and serve its URDF and tip, and a
// Cartesian jog of the ghost in the tool frame is planned and executed on it.
TEST(ConsoleApp, AUrdfArmIsJoggedPlannedAndExecuted) {
  test_files::TempDir tmp("console_arm");
  const fs::path dir = tmp.path();
  const std::string script = (dir / "plan.txt").string();
  std::ofstream(script) << "wait-until connected 30\n"
                           "wait-until in-control 10\n"
                           "ghost reset\n"
                           "plan add 0 start\n"
                           "ghost cartesian tool z 40mm\n"
                           "ghost cartesian base y -30mm\n"
                           "ghost gripper close\n"
                           "plan add 0.5 end\n"
                           "validate\n"
                           "execute\n"
                           "wait-until idle 30\n"
                           "screenshot " +
                               (dir / "arm.png").string() + "\n";
  ConsoleOptions options = telear::test::scripted_headless_console(script, kWidth, kHeight);
  options.arm = {"ur6", "", {}};
  std::ostringstream log;
  auto created = ConsoleApp::create(options, log);
  ASSERT_TRUE(created) << created.error().message;
  ConsoleApp& app = **created;
  session::Session& session = app.session();
  ASSERT_TRUE(run_until(app, 60, [&] { return app.script().finished(); })) << log.str();
  EXPECT_EQ(app.script().failures(), 0) << log.str();
  EXPECT_EQ(session.model().dof(), 6);
  EXPECT_EQ(session.model().name(), "ur6");

  // The plan's second waypoint is the start moved 40 mm along the tool's z, then 30 mm along
  // the base's -y: the Cartesian jog of the URDF arm's ghost.
  ASSERT_EQ(session.plan().size(), 2u);
  const core::RobotModel& model = session.model();
  const Eigen::Isometry3d T0 = core::tool_pose(model, session.plan().waypoint(0).q);
  const Eigen::Isometry3d T1 = core::tool_pose(model, session.plan().waypoint(1).q);
  const Eigen::Vector3d expected =
      T0.translation() + 0.04 * T0.linear().col(2) + Eigen::Vector3d(0, -0.03, 0);
  EXPECT_LT((T1.translation() - expected).norm(), 1e-4) << T1.translation().transpose();
  EXPECT_EQ(session.last_execution_result(), "completed");
  ASSERT_TRUE(session.view().real);
  EXPECT_LT(
      (session.view().real->state.q - session.plan().waypoints().back().q).cwiseAbs().maxCoeff(),
      0.01);

  // The robot server describes the arm it runs, so a remote client can draw it.
  auto info = session.robot().get_info();
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->tip_link, "tcp");
  EXPECT_THAT(info->urdf, HasSubstr("<robot"));

  // The ghost (the URDF arm's meshes, tinted) is drawn over the video.
  const core::Image& image = app.last_image();
  ASSERT_EQ(image.width, kWidth);
  const Stats view = region_stats(image, 10, 80, static_cast<int>(kWidth * 0.69) - 10,
                                  static_cast<int>(kHeight * 0.58) - 10);
  EXPECT_GT(view.stddev, 20.0);
  EXPECT_GT(view.cyan, 200);
  session.disconnect();
}

}  // namespace
}  // namespace telear::console
