// The console's Registration panel (issue 15), headless (EGL) against simulated servers on
// loopback (a robot server without a workspace, a vision server with the rig's calibration),
// driven by a UI script as `telear console --headless --script` runs it: open a
// capture, bring the real arm to poses (initialize, the direct jog), add them, solve; the
// capture is the Session's, the panel draws it (poses, per-eye detection, coverage, result).
//
// TELEAR_TEST_OUTPUT=DIR keeps the script and the screenshot there (docs/images is made by
// replaying that script under xvfb-run, docs/console.md).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/console_command.hpp"
#include "capture_test_rig.hpp"
#include "telear/console/console_actions.hpp"
#include "telear/console/console_app.hpp"
#include "telear/console/ui_script.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/session/capture_session.hpp"
#include "telear/session/registration_capture.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/capture_folder.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::console {
namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string degrees(const Eigen::VectorXd& q) {
  std::string out;
  for (int j = 0; j < q.size(); ++j) {
    if (j > 0) out += ',';
    out += core::format_fixed(core::degrees_from_radians(q[j]), 4);
  }
  return out;
}

TEST(RegistrationPanel, ScriptedCaptureAddsPosesShowsCoverageAndSolves) {
  const char* keep = std::getenv("TELEAR_TEST_OUTPUT");
  test_files::TempDir tmp("console_reg");
  const fs::path dir = keep ? fs::path(keep) : tmp.path();
  fs::create_directories(dir);
  const fs::path captures = dir / "captures";
  fs::remove_all(captures);
  const std::string shot = (dir / "console_registration.png").string();
  fs::remove(shot);

  // Where the operator starts (both cameras see the marker), then poses spread around it as
  // an operator would choose them (here: the automatic chooser with the rig's true cameras).
  auto loaded = test::load_puma_capture_rig();
  ASSERT_TRUE(loaded) << loaded.error().message;
  const core::RobotModel& model = *loaded->model;
  const sim::StereoRig& rig = loaded->rig;
  const core::MarkerMount& marker = loaded->marker;
  auto visible = test::marker_visible_start();
  ASSERT_TRUE(visible) << visible.error().message;
  Eigen::VectorXd start = *visible;
  const std::vector<Eigen::VectorXd> poses =
      session::choose_capture_poses(model, start, rig.cameras, marker, 16, 5);
  ASSERT_GE(poses.size(), 14u);

  // The servers: the simulated PUMA where the operator left it (no workspace: the poses are
  // the point here, not the table) and the rig serving its calibration, as a lab runs them.
  const std::string calibration = test::data_path("cameras/puma560_stereo.yaml");
  lab::EmbeddedServersOptions server_options;
  server_options.calibration_file = calibration;
  server_options.initial_q = start;
  server_options.fps = 10.0;
  auto servers = lab::EmbeddedServers::create(loaded->model, server_options);
  ASSERT_TRUE(servers) << servers.error().message;
  const std::string token_file = (dir / "token").string();
  std::ofstream(token_file) << (*servers)->token() << "\n";

  std::ostringstream script;
  script << "wait-until connected 30\n"
            "take-control\n"
            "registration add   # fails: no capture open (counted, the script goes on)\n"
            "registration open "
         << captures.string()
         << " qr:1   # fails: an unknown target\n"
            "registration open "
         << captures.string()
         << "\n"
            "real initialize "
         << degrees(start)
         << "\n"
            "wait-until idle 30\n"
            "registration add\n"
            "real jog joint 6 +10deg   # the direct jog, as the panel's buttons send it\n"
            "wait-until idle 10\n"
            "registration add\n"
            "registration solve   # fails: two poses (counted; the panel shows why)\n";
  for (const Eigen::VectorXd& q : poses) {
    script << "real initialize " << degrees(q) << "\nwait-until idle 30\nregistration add\n";
  }
  // An add while e-stopped fails on the capture's worker: reported on its line when done.
  script << "estop\n"
            "registration add\n"
            "reset-estop\n"
            "registration solve\n"
            "screenshot "
         << shot << "\n";
  const std::string script_file = (dir / "registration.txt").string();
  std::ofstream(script_file) << script.str();

  ConsoleOptions options;
  options.start_local_servers = cli::simulated_local_servers();  // as `telear console`
  options.headless = true;
  options.width = 1600;
  options.height = 1000;
  options.resolution = "320x240";  // the live view reduced; the capture asks for the full size
  options.robot = (*servers)->robot_address();
  options.vision = (*servers)->vision_address();
  options.token_file = token_file;
  options.calibration = calibration;
  options.lease_heartbeat_s = 1.0;  // the servers, renderer and solver share a loaded machine
  options.script = script_file;
  options.frames = 1000000;
  std::ostringstream log;
  auto created = ConsoleApp::create(options, log);
  ASSERT_TRUE(created) << created.error().message;
  ConsoleApp& app = **created;
  const auto begin = Clock::now();
  while (!app.script().finished()) {
    ASSERT_TRUE(app.frame()) << log.str();
    ASSERT_LT(std::chrono::duration<double>(Clock::now() - begin).count(), 300) << log.str();
  }
  EXPECT_EQ(app.script().failures(), 4) << log.str();
  EXPECT_THAT(log.str(), HasSubstr("line 3: registration add: no capture open: open one on a "
                                   "folder first"));
  EXPECT_THAT(log.str(), HasSubstr("line 4: registration open " + captures.string() +
                                   " qr:1: registration: target 'qr:1': unknown kind 'qr'"));
  EXPECT_THAT(log.str(), HasSubstr("line 12: registration solve: capture '"));
  EXPECT_THAT(log.str(), HasSubstr(": registration add: pose " + std::to_string(poses.size() + 2) +
                                   ": the robot is e-stopped"));

  // The capture is the Session's; the console only shows it.
  const session::CaptureSession* capture = app.session().capture();
  ASSERT_NE(capture, nullptr);
  EXPECT_TRUE(app.ui().show_registration);
  const int count = static_cast<int>(poses.size()) + 2;
  ASSERT_EQ(static_cast<int>(capture->poses().size()), count);
  // Some poses hide the marker (this chooser is not told the arm's body): shown, kept.
  EXPECT_GE(capture->detected().left_found, count / 2);
  EXPECT_GE(capture->detected().right_found, count / 2);
  ASSERT_TRUE(capture->solution()) << capture->last_solve_error();
  EXPECT_LT(capture->solution()->result.base_sigma.position_mm, 2.0);
  EXPECT_THAT(registration_summary(capture->solution()->result),
              HasSubstr(std::to_string(capture->solution()->result.views_used) + " poses"));

  // The folder is a capture `telear register --captures` reads, at the cameras' own size.
  auto folder = vision::load_capture_folder(captures.string());
  ASSERT_TRUE(folder) << folder.error().message;
  EXPECT_EQ(static_cast<int>(folder->poses.size()), count);
  auto images = vision::read_captured_images(captures.string(), folder->poses[0].frames[0]);
  ASSERT_TRUE(images) << images.error().message;
  EXPECT_EQ(images->left.cols, 640);

  // The screenshot: the panel with its coverage thumbnails (green where the marker was found).
  ASSERT_TRUE(fs::exists(shot));
  const core::Image& image = app.last_image();
  ASSERT_EQ(image.width, 1600);
  int green = 0;
  for (int y = 580; y < 970; ++y) {
    for (int x = 300; x < 1100; ++x) {
      const int r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
      green += g > r + 40 && g > b + 40;
    }
  }
  EXPECT_GT(green, 500) << "no coverage drawn in the Registration panel";

  // Another target, as the panel's target field sends it: the new capture detects it and
  // names it in its folder.
  UiState& ui = app.ui();
  const std::string board_folder = (dir / "board_captures").string();
  fs::remove_all(board_folder);
  ASSERT_TRUE(apply_action(app.session(), ui,
                           {.kind = ActionKind::kCaptureOpen,
                            .text = board_folder,
                            .spec = "charuco:5x5:0.06:0.045:4x4_50"})
                  .ok());
  ASSERT_NE(app.session().capture(), nullptr);
  EXPECT_EQ(app.session().capture()->target().spec(), "charuco:5x5:0.06:0.045:DICT_4X4_50");
  EXPECT_THAT(ui.last_message, HasSubstr("see the ChArUco board 5x5"));
  app.session().disconnect();
  EXPECT_EQ(app.session().capture(), nullptr);  // disconnecting closes the capture
}

TEST(RegistrationPanel, ScriptLinesParseAndExplainMistakes) {
  auto lines = parse_ui_script(
      "registration open caps\nregistration add\nregistration solve\n"
      "registration close\nregistration open board charuco:5x5:0.06:0.045:4x4_50\n",
      6, "s.txt");
  ASSERT_TRUE(lines) << lines.error().message;
  ASSERT_EQ(lines->size(), 5u);
  const auto& open = std::get<UiAction>((*lines)[0].step);
  EXPECT_EQ(open.kind, ActionKind::kCaptureOpen);
  EXPECT_EQ(open.text, "caps");
  EXPECT_EQ(open.spec, "");  // the robot's marker
  EXPECT_EQ(std::get<UiAction>((*lines)[3].step).kind, ActionKind::kCaptureClose);
  const auto& open_board = std::get<UiAction>((*lines)[4].step);
  EXPECT_EQ(open_board.text, "board");
  EXPECT_EQ(open_board.spec, "charuco:5x5:0.06:0.045:4x4_50");
  auto bad = parse_ui_script("registration open\n", 6, "s.txt");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message,
            "s.txt, line 1: registration open: usage: registration open FOLDER [TARGET]");
  bad = parse_ui_script("wait 1\nregistration undo\n", 6, "s.txt");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message,
            "s.txt, line 2: registration undo: unknown registration action 'undo' (open, add, "
            "solve, close)");
}

}  // namespace
}  // namespace telear::console
