// `telear demo` as the README runs it, at low resolution (issue 6's integration test): the
// pick-and-place plan executes on the simulated robot, tracking stays within tolerance, the
// calibration's overlay error is under target, the injected delay switches AR -> VR -> AR,
// the bytes saved are measured, the rehearsal into the table is refused naming the contact
// (issue 13), and the video, key frames and reports are written.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "telear/console/replay_app.hpp"
#include "telear/render/image_io.hpp"
#include "test_util/temp_dir.hpp"

namespace telear {
namespace {

using test::run_telear;
namespace fs = std::filesystem;

TEST(DemoCli, ThePickAndPlaceRunsEndToEndAndReportsItsFigures) {
  test_files::TempDir tmp("demo");
  const fs::path dir = tmp.file("out");
  const std::string d = dir.string();
  // The simulated cameras at 10 fps (the default 20 renders twice the frames for the same
  // checks: a quarter of the test's CPU time).
  const auto r = run_telear("demo --out " + d +
                            " --resolution 320x240 --delay-ms 700 --fps 10 --camera-fps 10" +
                            " --record " + d + "/task.mcap");
  ASSERT_EQ(r.exit_code, 0) << r.out << "\n" << r.err;
  EXPECT_NE(r.out.find("[7/7] writing the report"), std::string::npos) << r.out;

  std::ifstream in(d + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  // Executed and tracked.
  EXPECT_EQ(report["execution"]["result"], "completed");
  EXPECT_LT(report["execution"]["max_error_rad"].get<double>(),
            report["execution"]["tolerance_rad"].get<double>());
  EXPECT_GT(report["execution"]["samples"].get<int>(), 20);
  // Calibrated and registered from rendered images: every target of `telear eval` passes.
  EXPECT_TRUE(report["calibration"]["pass"].get<bool>());
  for (const char* eye : {"left", "right"}) {
    EXPECT_LT(report["calibration"][eye]["overlay_rms_px"].get<double>(), 0.5) << eye;
  }
  // Registered through the servers (issue 15): automatic poses captured through the robot and
  // vision servers, the marker found in nearly all of them; the cameras the AR view draws with
  // are these. Against the truth the chessboard calibration's focal length error (-0.03 %)
  // adds ~0.7 mm along the optical axis; with the rig's true intrinsics the registration's
  // own error is left (16 poses at 2 x 2 anti-aliasing: 0.2-0.6 mm, docs/demo.md; issue 15's
  // 0.5 mm is asserted at 24 poses by session_registration_capture_test). The bundle
  // adjustment beats OpenCV's closed form on the same images.
  const auto& registration = report["registration"];
  ASSERT_TRUE(registration.is_object()) << report.dump(1);
  EXPECT_EQ(registration["poses_requested"], 16);
  EXPECT_GE(registration["poses_used"].get<int>(), 13) << registration;
  EXPECT_GT(registration["capture_s"].get<double>(), 0.0);
  for (const char* eye : {"left", "right"}) {
    EXPECT_LT(registration[eye]["registration_mm"].get<double>(), 1.2) << eye;
    EXPECT_LT(registration[eye]["overlay_rms_px"].get<double>(), 0.1) << eye;
    EXPECT_LT(registration[eye]["registration_mm"].get<double>(),
              registration[eye]["shah_li_mm"].get<double>())
        << eye;
    EXPECT_LT(registration["true_intrinsics"][eye]["registration_mm"].get<double>(), 0.8) << eye;
    EXPECT_LT(registration["true_intrinsics"][eye]["registration_deg"].get<double>(), 0.05) << eye;
    EXPECT_DOUBLE_EQ(registration[eye]["registration_mm"].get<double>(),
                     report["calibration"][eye]["registration_mm"].get<double>());
  }
  EXPECT_NE(r.out.find("poses captured through the servers"), std::string::npos) << r.out;
  // The live residual's checks, each with the arm at rest or moving at the frame (issue 26:
  // at 320x240 the marker may be too small to find; the split is what is checked here).
  for (const char* eye : {"left", "right"}) {
    const auto& live = report["overlay_error_live"][eye];
    EXPECT_EQ(live["checks_at_rest"].get<int>() + live["checks_moving"].get<int>(),
              live["checks"].get<int>())
        << live;
  }
  EXPECT_NE(test::slurp(d + "/report.md").find("| ... with the arm at rest / moving | "),
            std::string::npos);
  // Issue 22: the task recorded to MCAP beside the report (its content is checked by the
  // reference reader in tests/record): states at >= 30 Hz over the task, the video, the
  // session's own events.
  const auto& recording = report["recording"];
  ASSERT_TRUE(recording.is_object()) << report.dump(1).substr(0, 2000);
  EXPECT_EQ(recording["dropped"], 0);
  EXPECT_EQ(recording["bytes"].get<std::uintmax_t>(), fs::file_size(d + "/task.mcap"));
  EXPECT_GE(recording["messages"]["/robot/joint_states"].get<double>(),
            30.0 * report["execution"]["plan_duration_s"].get<double>());
  EXPECT_GT(recording["messages"]["/camera/left/image/compressed"].get<int>(), 20);
  EXPECT_GT(recording["messages"]["/telear/latency"].get<int>(), 20);  // the session's frames
  EXPECT_GT(recording["messages"]["/ghost/joint_states"].get<int>(), 0);
  EXPECT_GT(recording["messages"]["/events"].get<int>(), 3);
  EXPECT_EQ(test::slurp(d + "/task.mcap").substr(0, 8), std::string("\x89MCAP0\r\n", 8));
  // ... and plotted by `telear report` into the same folder, report.md showing the plots.
  EXPECT_EQ(recording["plot_error"], "");
  EXPECT_EQ(recording["summary"], "recording_report.md");
  ASSERT_EQ(recording["plots"].size(), 5u) << recording;
  for (const auto& plot : recording["plots"]) {
    const std::string name = plot.get<std::string>();
    EXPECT_GT(fs::file_size(d + "/" + name), 1000u) << name;
    EXPECT_NE(test::slurp(d + "/report.md").find("](" + name + ")"), std::string::npos) << name;
  }
  EXPECT_NE(test::slurp(d + "/recording_report.md").find("| shoulder | deg | "), std::string::npos);
  EXPECT_FALSE(fs::exists(d + "/session.mcap"));  // --record named another file
  // The injected delay (issue 23, predict first): the late video stayed in AR while the plan
  // ran, the arm predicted over it; once the plan was over the still late video switched to
  // VR, and back after the delay.
  EXPECT_GT(report["display"]["predicted_late_s"].get<double>(), 0.5) << report["display"];
  EXPECT_GE(report["display"]["ar_to_vr"].get<int>(), 1);
  EXPECT_GE(report["display"]["vr_to_ar"].get<int>(), 2);  // the start, and after the delay
  bool vr_after_the_plan = false;
  for (const auto& s : report["display"]["switches"]) {
    if (s["to"] == "VR" && s["reason"].get<std::string>().rfind("video late", 0) == 0) {
      vr_after_the_plan = true;
    }
  }
  EXPECT_TRUE(vr_after_the_plan) << report["display"];
  // Issue 23: with the states late too, the view drew the predicted arm (its key frame), nearer
  // the simulator's truth than the delayed state (docs/demo.md has the figures).
  const auto& prediction = report["prediction"];
  ASSERT_TRUE(prediction.is_object()) << report.dump(1).substr(0, 2000);
  EXPECT_GT(prediction["frames_predicted"].get<int>(), 5) << prediction;
  EXPECT_LT(prediction["tool_error_mm_p95_predicted"].get<double>(),
            prediction["tool_error_mm_p95_unpredicted"].get<double>())
      << prediction;
  EXPECT_TRUE(fs::exists(d + "/keyframe_5b_predicted.png"));
  // The plan is the message (issue 14): the measured message is the computed one, far fewer
  // bytes than 100 Hz jogs or its 100 Hz samples; the robot ran exactly the trajectory the
  // preview showed.
  const auto& bytes = report["bytes"];
  // (The computed one assumes a 10-digit plan id; the session's ids carry a 19-digit epoch.)
  EXPECT_NEAR(bytes["plan_message_measured"].get<double>(), bytes["plan_message"].get<double>(),
              16.0);
  EXPECT_GT(bytes["plan_message_measured"].get<double>(), 100.0);
  // Issue 14's goal: 101x measured (676 B against 68,244 B, docs/demo.md; the hash travels as
  // the digest's 32 bytes, not 64 hex digits); a regression to samples would be ~1.6x.
  EXPECT_GE(bytes["ratio"].get<double>(), 100.0) << bytes;
  EXPECT_GE(bytes["ratio_vs_samples"].get<double>(), 20.0) << bytes;
  EXPECT_TRUE(report["execution"]["executed_is_previewed"].get<bool>());
  EXPECT_EQ(report["execution"]["executed_hash"].get<std::string>().size(), 64u);
  EXPECT_LT(report["execution"]["max_command_deviation_rad"].get<double>(), 1e-3);
  EXPECT_GT(report["video"]["frames_shown"].get<int>(), 20);
  // The outputs. The MP4 is H.264 so that browsers play it: Debian's OpenCV writes it through
  // FFmpeg's libx264 (fourcc avc1); a fallback to MPEG-4 part 2 would be recorded here.
  EXPECT_GT(fs::file_size(d + "/demo_stereo.mp4"), 10000u);
  EXPECT_EQ(report["outputs"]["video_codec"], "avc1");
  EXPECT_EQ(report["outputs"]["video_warning"], "");
  const std::string mp4 = test::slurp(d + "/demo_stereo.mp4");
  EXPECT_NE(mp4.find("avcC"), std::string::npos);  // the H.264 decoder configuration box
  EXPECT_EQ(mp4.find("mp4v"), std::string::npos);
  EXPECT_NE(test::slurp(d + "/report.md").find("avc1"), std::string::npos);
  EXPECT_GE(report["outputs"]["key_frames"].size(), 5u);
  for (const auto& frame : report["outputs"]["key_frames"]) {
    EXPECT_TRUE(fs::exists(frame.get<std::string>())) << frame;
  }
  EXPECT_TRUE(fs::exists(d + "/report.md"));
  // Issue 22: the task's recording replayed at each key frame's time draws the key frame's view,
  // pixel for pixel, from the recorded frame, ghost, arm and calibration (the collision key
  // frame's red contact links excepted: replay runs no collision checker).
  console::ReplayOptions replay_options;
  replay_options.path = d + "/task.mcap";
  replay_options.headless = true;
  replay_options.width = 640;
  replay_options.height = 400;
  std::ostringstream replay_log;
  auto replay = console::ReplayApp::create(replay_options, replay_log);
  ASSERT_TRUE(replay) << replay.error().message;
  int replayed = 0;
  for (const auto& key_frame : report["recording"]["key_frames"]) {
    const std::string file = key_frame["file"].get<std::string>();
    if (file.find("collision") != std::string::npos) continue;
    // Issue 23: replay draws no predicted arm, and a recording holds the robot's states as the
    // session received them, not as it held them back (keyframe_5b_predicted, and any key frame
    // drawn while the demo held the states back: on a loaded machine the VR key frame can be).
    if (key_frame.value("predicted", false) || key_frame.value("states_held_back", false)) {
      continue;
    }
    (*replay)->seek(key_frame["t_s"].get<double>());
    auto drawn = (*replay)->render_view();
    ASSERT_TRUE(drawn) << drawn.error().message;
    auto live = render::read_image(d + "/" + file);
    ASSERT_TRUE(live) << live.error().message;
    ASSERT_EQ(drawn->width, live->width) << file;
    ASSERT_EQ(drawn->height, live->height) << file;
    EXPECT_EQ(drawn->pixels, live->pixels) << file << " at " << key_frame["t_s"] << " s";
    ++replayed;
  }
  EXPECT_GE(replayed, 5) << report["recording"];
  // Issue 13 on the default PUMA: the first rehearsal, into the table beside the box, fails
  // on its first contact (a finger in the table top), shown red on the ghost in its own key
  // frame; the corrected plan (elbow-up to the box far out on the table,
  // data/workspaces/puma560_table.yaml) is collision-free and executed.
  ASSERT_TRUE(report.contains("collision")) << report.dump(1);
  const auto& first = report["collision"]["first_rehearsal"];
  EXPECT_FALSE(first["collision_free"].get<bool>()) << first;
  EXPECT_EQ(first["object"], "table_top") << first;
  EXPECT_NE(first["link"].get<std::string>().find("finger"), std::string::npos) << first;
  EXPECT_GT(first["time_s"].get<double>(), 0.0);
  EXPECT_GT(first["depth_m"].get<double>(), 0.0);
  const auto& final_plan = report["collision"]["final_plan"];
  EXPECT_TRUE(final_plan["collision_free"].get<bool>()) << final_plan;
  EXPECT_GT(final_plan["min_clearance_m"].get<double>(), 0.005) << final_plan;
  EXPECT_FALSE(final_plan["link"].get<std::string>().empty());
  EXPECT_TRUE(fs::exists(d + "/keyframe_2a_collision.png"));
  bool collision_key_frame_listed = false;
  for (const auto& frame : report["outputs"]["key_frames"]) {
    collision_key_frame_listed =
        collision_key_frame_listed ||
        frame.get<std::string>().find("keyframe_2a_collision") != std::string::npos;
  }
  EXPECT_TRUE(collision_key_frame_listed) << report["outputs"]["key_frames"];
  EXPECT_NE(r.out.find("validation of the first rehearsal: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("hits table_top"), std::string::npos) << r.out;
  EXPECT_NE(
      test::slurp(d + "/report.md").find("- collision: the first rehearsal, first contact at t = "),
      std::string::npos);

  // The calibration is cached for the next run (OUT/cache, key.txt written last). That a
  // matching cache is reused is CalibrationPipeline's test (tests/lab): a second whole demo
  // here would check little more for another minute of CI.
  EXPECT_NE(r.out.find("written to " + d + "/cache"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "cache" / "key.txt"));
  EXPECT_TRUE(fs::exists(dir / "cache" / "stereo.yaml"));
  EXPECT_FALSE(report["calibration_cached"].get<bool>());
}

// Issue 12: the same workflow with a shipped URDF arm: the 7-DOF arm with its mimic-joint
// gripper is calibrated, registered from its own marker, rehearsed (redundant IK), executed
// and monitored on its own simulated rig. It is given as its robot file with the robot
// options every command takes (--tip, --package-path), which reach the whole workflow.
TEST(DemoCli, TheSevenJointUrdfArmRunsTheSameWorkflow) {
  test_files::TempDir tmp("demo_arm7");
  const fs::path dir = tmp.file("out");
  const std::string d = dir.string();
  const std::string robots = std::string(TELEAR_TEST_DATA_DIR) + "/robots";
  const auto r = run_telear(
      "demo --robot " + robots + "/arm7.yaml --tip tcp --package-path " + robots + " --out " + d +
      " --resolution 320x240 --delay-ms 0 --fps 10 --camera-fps 10 --no-video");
  ASSERT_EQ(r.exit_code, 0) << r.out << "\n" << r.err;
  std::ifstream in(d + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["robot"]["name"], "arm7");
  EXPECT_EQ(report["robot"]["dof"], 7);
  EXPECT_EQ(report["robot"]["tip_link"], "tcp");
  EXPECT_EQ(report["execution"]["result"], "completed");
  EXPECT_LT(report["execution"]["max_error_rad"].get<double>(),
            report["execution"]["tolerance_rad"].get<double>());
  EXPECT_TRUE(report["calibration"]["pass"].get<bool>());
  for (const char* eye : {"left", "right"}) {
    EXPECT_LT(report["calibration"][eye]["registration_mm"].get<double>(), 1.0) << eye;
    // The marker the rig renders on the arm's flange is found in the live video.
    EXPECT_GT(report["overlay_error_live"][eye]["checks"].get<int>(), 0) << eye;
  }
  // Issue 13: the session checks collisions. The first rehearsal, into the tray, fails on its
  // first contact (a finger in the tray), shown red on the ghost in its own key frame; the
  // executed plan is collision-free, its smallest clearance to the workspace reported.
  ASSERT_TRUE(report.contains("collision")) << report.dump(1);
  const auto& first = report["collision"]["first_rehearsal"];
  EXPECT_FALSE(first["collision_free"].get<bool>()) << first;
  EXPECT_EQ(first["object"], "tray") << first;
  EXPECT_NE(first["link"].get<std::string>().find("finger"), std::string::npos) << first;
  EXPECT_GT(first["time_s"].get<double>(), 0.0);
  EXPECT_GT(first["depth_m"].get<double>(), 0.0);
  const auto& final_plan = report["collision"]["final_plan"];
  EXPECT_TRUE(final_plan["collision_free"].get<bool>()) << final_plan;
  EXPECT_GT(final_plan["min_clearance_m"].get<double>(), 0.005) << final_plan;
  EXPECT_FALSE(final_plan["link"].get<std::string>().empty());
  EXPECT_TRUE(fs::exists(d + "/keyframe_2a_collision.png"));
  EXPECT_NE(r.out.find("validation of the first rehearsal: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("hits tray"), std::string::npos) << r.out;
  std::ifstream md(d + "/report.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("- collision: the first rehearsal, first contact at t = "), std::string::npos)
      << text;
  // Recorded by default (OUT/session.mcap) and plotted: the tracking error of its seven joints.
  EXPECT_EQ(report["recording"]["path"], d + "/session.mcap");
  EXPECT_TRUE(fs::exists(d + "/session.mcap"));
  EXPECT_NE(text.find("](tracking_error.png)"), std::string::npos) << text;
}

// Issue 26: the UR-type arm, the third shipped arm, end to end. Its demo exited at the
// registration through the servers: the capture started at a sampled configuration with the
// base inside the upper arm (its +-360 deg joints), where the robot server refused every move.
TEST(DemoCli, TheUrTypeArmRunsTheSameWorkflow) {
  test_files::TempDir tmp("demo_ur6");
  const std::string d = tmp.file("out");
  const auto r =
      run_telear("demo --robot ur6 --out " + d +
                 " --resolution 320x240 --delay-ms 0 --fps 10 --camera-fps 10 --no-video");
  ASSERT_EQ(r.exit_code, 0) << r.out << "\n" << r.err;
  std::ifstream in(d + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["robot"]["name"], "ur6");
  EXPECT_EQ(report["execution"]["result"], "completed");
  EXPECT_TRUE(report["calibration"]["pass"].get<bool>());
  EXPECT_GE(report["registration"]["poses_captured"].get<int>(), 8);
  for (const char* eye : {"left", "right"}) {
    EXPECT_LT(report["registration"][eye]["registration_mm"].get<double>(), 2.0) << eye;
  }
  EXPECT_EQ(r.err.find("touches link"), std::string::npos) << r.err;
}

TEST(DemoCli, BadOptionsAreRefusedWithTheReason) {
  test_files::TempDir tmp("demo_bad");
  const std::string bad = tmp.file("out");
  auto r = run_telear("demo --resolution 20x10 --out " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("telear demo: --resolution: '20x10' is outside 64x48 .. 1920x1080"),
            std::string::npos)
      << r.err;
  r = run_telear("demo --delay-ms -5 --out " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("delay_ms -5 is outside 0..5000"), std::string::npos) << r.err;
  r = run_telear("demo --live-multisample 0 --out " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the live video's multisampling 0 is outside 1..16"), std::string::npos)
      << r.err;
  // A robot without a simulated rig: the demo cannot film it, and says so before any work.
  r = run_telear("demo --robot " + std::string(TELEAR_TEST_FILES_DIR) +
                 "/urdf/fixed_chain.urdf --out " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("has no simulated rig"), std::string::npos) << r.err;
  // The robot options of every command (issue 12), checked before any work: a tree with
  // several leaves names its candidate tips, a tip that is not a link is named, and
  // --missing-meshes takes error or primitives.
  r = run_telear("demo --robot " + std::string(TELEAR_TEST_FILES_DIR) +
                 "/urdf/branching_tip.urdf --out " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the tree has several leaf links (a, b, tcp); name the tip link"),
            std::string::npos)
      << r.err;
  r = run_telear("demo --robot arm7 --tip nosuch --out " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("has no link named 'nosuch'"), std::string::npos) << r.err;
  // Recording is the default; --no-record turns it off, and cannot go with --record.
  r = run_telear("demo --no-record --record " + bad + "/x.mcap --out " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("telear demo: --record excludes --no-record"), std::string::npos) << r.err;
  r = run_telear("demo --missing-meshes maybe --out " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "telear demo: --missing-meshes: maybe not in {error,primitives}\n");
}

}  // namespace
}  // namespace telear
