// The session recorder against running servers (a simulated PUMA behind a real robot server, a
// synthetic stereo source behind a real vision server), its file read back by the reference
// reader (npm's @mcap/core) and every message decoded with the file's own schemas
// (tests/record/js/decode_recording.mjs), as Foxglove reads it.

#include "telear/record/session_recorder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "telear/core/clock.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/workspace.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/robot_server.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/net/vision_server.hpp"
#include "telear/record/recording_topics.hpp"
#include "telear/sim/sim_robot_driver.hpp"
#include "telear/vision/synthetic_source.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::record {
namespace {

using ::testing::Contains;
using ::testing::HasSubstr;

constexpr const char* kToken = "recorder-test-token";

// `node decode_recording.mjs FILE` as JSON (the test fails on a reader error).
nlohmann::json decode(const std::string& path) {
  const std::string command = std::string("cd '") + TELEAR_RECORD_JS_DIR +
                              "' && /usr/bin/node decode_recording.mjs '" + path + "' 2>&1";
  std::string output;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[65536];
    std::size_t n = 0;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
    pclose(pipe);
  }
  auto json = nlohmann::json::parse(output, nullptr, false);
  EXPECT_FALSE(json.is_discarded()) << "node printed: " << output.substr(0, 2000);
  return json.is_discarded() ? nlohmann::json::object() : json;
}

struct Servers {
  std::unique_ptr<net::RobotServer> robot;
  std::unique_ptr<net::VisionServer> vision;
};

Servers start_servers(const test_files::TempDir& tmp) {
  Servers s;
  auto description = core::load_robot_description({"puma560"});
  EXPECT_TRUE(description.ok()) << description.error().message;
  sim::SimRobotDriverOptions driver_options;
  driver_options.urdf = core::urdf_text_for_clients(*description);  // served by GetInfo
  auto driver = sim::SimRobotDriver::create(description->model, driver_options);
  EXPECT_TRUE(driver.ok()) << driver.error().message;
  net::RobotServerOptions robot_options;
  robot_options.listen_address = "127.0.0.1:0";
  robot_options.token = kToken;
  robot_options.robot_description = *description;
  robot_options.workspace_file = core::default_workspace_file("puma560");
  auto robot = net::RobotServer::create(std::move(driver).value(), robot_options);
  EXPECT_TRUE(robot.ok()) << robot.error().message;
  s.robot = std::move(robot).value();

  vision::SyntheticSourceOptions source_options;
  source_options.width = 160;
  source_options.height = 120;
  source_options.fps = 30;
  auto source = vision::SyntheticSource::create(source_options);
  EXPECT_TRUE(source.ok()) << source.error().message;
  net::VisionServerOptions vision_options;
  vision_options.listen_address = "127.0.0.1:0";
  vision_options.token_file = tmp.write("token", std::string(kToken) + "\n");
  vision_options.source = std::move(source).value();
  vision_options.calibration_file = test::data_path("cameras/puma560_stereo.yaml");
  auto vision = net::VisionServer::create(std::move(vision_options));
  EXPECT_TRUE(vision.ok()) << vision.error().message;
  s.vision = std::move(vision).value();
  return s;
}

TEST(SessionRecorder, ARecordingOfRunningServersDecodesWithItsOwnSchemas) {
  test_files::TempDir tmp("session_recorder");
  Servers servers = start_servers(tmp);
  ASSERT_TRUE(servers.robot && servers.vision);
  const std::string path = tmp.file("session.mcap");

  // The operator: holds the lease and rehearses on its ghost.
  net::RobotClientOptions holder_options;
  holder_options.address = servers.robot->address();
  holder_options.token = kToken;
  holder_options.client_name = "operator";
  net::RobotClient holder(holder_options);
  holder.start();
  Eigen::VectorXd ghost(6);
  ghost << 0.1, 0.5, -0.4, 0.0, 0.3, 0.2;
  holder.set_ghost(ghost, 0.25);
  // A 1 s heartbeat: a loaded machine (CI) may starve a 100 ms one and lapse the lease, and the
  // ghost goes with it.
  ASSERT_TRUE(holder.acquire_lease(1.0));

  // The recorder's own clients, as `telear record` has them.
  net::RobotClientOptions robot_options = holder_options;
  robot_options.client_name = "recorder";
  robot_options.state_rate_hz = 50;
  net::RobotClient robot(robot_options);
  robot.start();
  auto info = robot.get_info();
  ASSERT_TRUE(info) << info.error().message;
  // The holder's ghost reaches the state stream with its first renewal (a third of the period).
  std::uint64_t seen = 0;
  const std::int64_t wait_start = core::monotonic_ns();
  while (true) {
    auto s = robot.wait_state(seen, 0.1);
    if (s && s->ghost_q.size() == 6) break;
    if (s) seen = s->sequence;
    ASSERT_LT(core::monotonic_ns() - wait_start, 5'000'000'000) << "no ghost in the state stream";
  }
  std::atomic<SessionRecorder*> sink{nullptr};
  net::VisionClientOptions vision_options;
  vision_options.address = servers.vision->address();
  vision_options.token = kToken;
  vision_options.on_received = [&sink](const net::ReceivedStereoFrame& f) {
    if (SessionRecorder* r = sink.load()) r->add_frame(f);
  };
  net::VisionClient vision(vision_options);
  auto camera_info = vision.get_camera_info();
  ASSERT_TRUE(camera_info && camera_info->found);

  RecordedSetup setup;
  setup.robot = *info;
  setup.cameras = camera_info->cameras;
  setup.calibration_yaml = camera_info->calibration_yaml;
  SessionRecorderOptions options;
  options.path = path;
  auto recorder = SessionRecorder::create(options, setup);
  ASSERT_TRUE(recorder) << recorder.error().message;
  sink = recorder->get();
  vision.start();
  const std::int64_t start = core::monotonic_ns();
  std::uint64_t state_after = 0, frame_after = 0;
  bool stopped = false;
  while (core::monotonic_ns() - start < 1'500'000'000) {
    if (auto s = robot.wait_state(state_after, 0.02)) {
      state_after = s->sequence;
      (*recorder)->add_state(*s);
    }
    if (auto f = vision.wait_frame(frame_after, 0.0)) {
      frame_after = f->second;
      (*recorder)->add_latency(*f->first);
    }
    if (!stopped && core::monotonic_ns() - start > 700'000'000) {
      stopped = true;
      ASSERT_TRUE(holder.estop("recorder test"));
    }
  }
  (*recorder)->add_log(LogLevel::kInfo, "the test's own line", core::monotonic_ns());
  vision.stop();
  sink = nullptr;
  auto counts = (*recorder)->close();
  ASSERT_TRUE(counts) << counts.error().message;
  EXPECT_TRUE(counts->dropped.empty());
  EXPECT_EQ(counts->bytes, std::filesystem::file_size(path));

  const nlohmann::json file = decode(path);
  ASSERT_FALSE(file.contains("error")) << file.dump(1).substr(0, 4000);
  const auto& topics = file["topics"];
  // Every message decoded, as many as were written, under Foxglove's schema names.
  for (const auto& [topic, n] : counts->written) {
    EXPECT_EQ(topics[topic]["count"].get<std::uint64_t>(), n) << topic;
  }
  EXPECT_EQ(topics[std::string(kTopicLeftImage)]["schema"], "foxglove.CompressedImage");
  EXPECT_EQ(topics[std::string(kTopicRobotJointStates)]["schema"], "foxglove.JointStates");
  EXPECT_EQ(topics[std::string(kTopicTransforms)]["schema"], "foxglove.FrameTransforms");
  EXPECT_EQ(topics[std::string(kTopicWorkspace)]["schema"], "foxglove.SceneUpdate");
  EXPECT_EQ(topics[std::string(kTopicLatency)]["schema"], "telear.record.v1.LatencyStages");

  // The state stream at >= 30 Hz over the 1.5 s; the ghost with it, as the operator set it.
  const auto& joints = topics[std::string(kTopicRobotJointStates)];
  EXPECT_GE(joints["count"].get<int>(), 45);
  ASSERT_EQ(joints["first"]["joints"].size(), 7u);  // six joints and the gripper
  EXPECT_EQ(joints["first"]["joints"][0]["name"], info->joints[0].name);
  EXPECT_EQ(joints["first"]["joints"][6]["name"], "gripper");
  // The servo's command with every state (the tracking error is the difference).
  EXPECT_EQ(topics[std::string(kTopicRobotJointCommands)]["count"], joints["count"]);
  EXPECT_EQ(topics[std::string(kTopicRobotJointCommands)]["schema"], "foxglove.JointStates");
  const auto& ghosts = topics[std::string(kTopicGhostJointStates)];
  EXPECT_GE(ghosts["count"].get<int>(), 40);
  for (int i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(ghosts["last"]["joints"][i]["position"].get<double>(), ghost[i]) << i;
  }
  EXPECT_DOUBLE_EQ(ghosts["last"]["joints"][6]["position"].get<double>(), 0.25);

  // Video: every frame received, both eyes, each a whole JPEG; the calibration with it.
  const auto& left = topics[std::string(kTopicLeftImage)];
  EXPECT_GE(left["count"].get<int>(), 30);
  EXPECT_EQ(left["count"], topics[std::string(kTopicRightImage)]["count"]);
  EXPECT_EQ(left["first"]["format"], "jpeg");
  EXPECT_EQ(left["first"]["frame_id"], "camera_left");
  EXPECT_TRUE(file["jpeg_ok"][std::string(kTopicLeftImage)].get<bool>());
  EXPECT_TRUE(file["jpeg_ok"][std::string(kTopicRightImage)].get<bool>());
  const auto& calibration = topics[std::string(kTopicLeftCalibration)];
  EXPECT_GE(calibration["count"].get<int>(), 1);
  EXPECT_DOUBLE_EQ(calibration["first"]["K"][0].get<double>(), camera_info->cameras.left.fx);
  EXPECT_EQ(calibration["first"]["width"].get<int>(), camera_info->cameras.left.width);
  EXPECT_GE(topics[std::string(kTopicLatency)]["count"].get<int>(), 10);

  // Transforms: every link of the arm and of the ghost under the URDF's root, the cameras.
  const auto& frames = file["frames"][std::string(kTopicTransforms)];
  EXPECT_THAT(frames, Contains(HasSubstr(">link6")));
  EXPECT_THAT(frames, Contains(HasSubstr(">ghost/link6")));
  EXPECT_THAT(frames, Contains(HasSubstr(">camera_left")));

  // The workspace as entities; the events a passive observer sees; the test's own line.
  auto workspace = core::load_workspace_file(core::default_workspace_file("puma560"));
  ASSERT_TRUE(workspace) << workspace.error().message;
  EXPECT_EQ(topics[std::string(kTopicWorkspace)]["first"]["entities"].size(),
            workspace->objects.size());
  EXPECT_THAT(file["events"], Contains(HasSubstr("operator holds the lease")));
  EXPECT_THAT(file["events"], Contains(HasSubstr("e-stop: recorder test")));
  EXPECT_THAT(file["events"], Contains("the test's own line"));
  EXPECT_THAT(file["attachments"], Contains("robot.urdf"));
  EXPECT_THAT(file["attachments"], Contains("calibration.yaml"));
  EXPECT_EQ(file["metadata"]["telear.session"]["robot"], info->model_name);
  EXPECT_EQ(file["metadata"]["telear.recording"]["dropped_total"], "0");
}

struct CommandRun {
  int exit_code = -1;
  std::string out;
};

CommandRun run_telear(const std::string& arguments) {
  CommandRun r;
  const std::string command = std::string(TELEAR_BINARY) + " " + arguments + " 2>&1";
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    std::size_t n = 0;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) r.out.append(buffer, n);
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  return r;
}

// `telear record` as the README runs it: a passive observer of running servers for --seconds.
TEST(RecordCli, RecordsRunningServersForTheGivenSeconds) {
  test_files::TempDir tmp("record_cli");
  Servers servers = start_servers(tmp);
  ASSERT_TRUE(servers.robot && servers.vision);
  const std::string token = tmp.write("token", std::string(kToken) + "\n");
  const std::string path = tmp.file("cli.mcap");
  const CommandRun r = run_telear("record --robot " + servers.robot->address() + " --vision " +
                                  servers.vision->address() + " --token-file " + token + " -o " +
                                  path + " --seconds 1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("recording " + servers.robot->address() + " and "));
  EXPECT_THAT(r.out, HasSubstr("wrote " + path + ": "));
  const nlohmann::json file = decode(path);
  ASSERT_FALSE(file.contains("error")) << file.dump(1).substr(0, 4000);
  EXPECT_GE(file["topics"][std::string(kTopicRobotJointStates)]["count"].get<int>(), 30);
  EXPECT_GE(file["topics"][std::string(kTopicLeftImage)]["count"].get<int>(), 10);
  EXPECT_EQ(file["metadata"]["telear.session"]["recorded_by"], "telear record");

  // Errors: a server that does not answer (exit 1, named), a bad option (exit 2).
  CommandRun bad =
      run_telear("record --robot 127.0.0.1:1 -o " + tmp.file("x.mcap") + " --seconds 1");
  EXPECT_EQ(bad.exit_code, 1) << bad.out;
  EXPECT_THAT(bad.out, HasSubstr("telear record: recording: robot server 127.0.0.1:1: "));
  EXPECT_FALSE(std::filesystem::exists(tmp.file("x.mcap")));
  bad = run_telear("record --robot " + servers.robot->address() + " -o " + tmp.file("y.mcap") +
                   " --token-file " + tmp.file("missing"));
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  EXPECT_THAT(bad.out, HasSubstr("telear record: --token-file: "));
}

// A writer that cannot keep up: new items are dropped, never waited for, and the file says how
// many (its telear.recording metadata and a warning on /events).
TEST(SessionRecorder, AFullQueueDropsAndCountsInsteadOfWaiting) {
  test_files::TempDir tmp("recorder_drops");
  auto description = core::load_robot_description({"puma560"});
  ASSERT_TRUE(description);
  RecordedSetup setup;
  setup.robot.model_name = "puma560";
  setup.robot.urdf = core::urdf_text_for_clients(*description);
  for (const core::Joint& j : description->model->joints()) setup.robot.joints.push_back({j.name});
  SessionRecorderOptions options;
  options.path = tmp.file("drops.mcap");
  options.queue_bytes = 1;  // one item at a time
  auto recorder = SessionRecorder::create(options, setup);
  ASSERT_TRUE(recorder) << recorder.error().message;
  const std::string jpeg(200'000, '\x55');
  constexpr int kFrames = 300;
  for (int i = 0; i < kFrames; ++i) {
    net::ReceivedStereoFrame f;
    f.frame_id = static_cast<std::uint64_t>(i + 1);
    f.jpeg_left = &jpeg;
    f.jpeg_right = &jpeg;
    f.capture_ns_left = f.capture_ns_right = f.receive_ns = core::monotonic_ns();
    (*recorder)->add_frame(f);
  }
  auto counts = (*recorder)->close();
  ASSERT_TRUE(counts) << counts.error().message;
  const std::string left(kTopicLeftImage);
  const std::uint64_t dropped = counts->dropped[left];
  EXPECT_GT(dropped, 0u);
  EXPECT_EQ(counts->written[left] + dropped, static_cast<std::uint64_t>(kFrames));
  const nlohmann::json file = decode(options.path);
  ASSERT_FALSE(file.contains("error")) << file.dump(1).substr(0, 4000);
  EXPECT_EQ(file["metadata"]["telear.recording"]["dropped_total"], std::to_string(dropped));
  EXPECT_EQ(file["metadata"]["telear.recording"]["dropped " + left], std::to_string(dropped));
  EXPECT_THAT(file["events"],
              Contains(HasSubstr("the recorder dropped " + std::to_string(dropped) + " items")));
  EXPECT_EQ(file["topics"][left]["count"].get<std::uint64_t>(), counts->written[left]);
}

TEST(SessionRecorder, RefusesARobotWithoutAUrdfAndAnUnwritablePath) {
  RecordedSetup setup;
  SessionRecorderOptions options;
  options.path = "/tmp/never.mcap";
  auto no_urdf = SessionRecorder::create(options, setup);
  ASSERT_FALSE(no_urdf);
  EXPECT_THAT(no_urdf.error().message, HasSubstr("the robot server sent no URDF"));
  auto description = core::load_robot_description({"puma560"});
  ASSERT_TRUE(description);
  setup.robot.urdf = core::urdf_text_for_clients(*description);
  setup.robot.joints.resize(6);
  options.path = "/nonexistent/dir/session.mcap";
  auto unwritable = SessionRecorder::create(options, setup);
  ASSERT_FALSE(unwritable);
  EXPECT_THAT(unwritable.error().message, HasSubstr("/nonexistent/dir/session.mcap"));
}

}  // namespace
}  // namespace telear::record
