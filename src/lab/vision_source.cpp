#include "telear/lab/vision_source.hpp"

#include <utility>

#include "telear/net/token_file.hpp"
#include "telear/sim/sim_rig_source.hpp"
#include "telear/vision/synthetic_source.hpp"
#include "telear/vision/videoio.hpp"

namespace telear::lab {
namespace {

Status open_sim(const VisionSourceOptions& options, VisionSource& opened) {
  sim::SimRigSourceOptions sim;
  sim.rig = options.rig;
  if (options.fps > 0) sim.fps = options.fps;
  sim.supersample = options.supersample;
  sim.noise_sigma = options.noise;
  sim.frame_code = options.frame_code;
  if (options.size) {
    // Constructed in place from the literal: a moved temporary std::string here trips GCC 12's
    // -Warray-bounds false positive once the unity build inlines it.
    opened.warnings.emplace_back(
        "the size is ignored for the sim source (the rig file sets the cameras' size); "
        "clients may ask for a scaled stream");
  }
  if (!options.robot_server.empty()) {
    net::RobotClientOptions robot_options;
    robot_options.address = options.robot_server;
    robot_options.client_name = "telear-vision-server";
    if (!options.robot_token_file.empty()) {
      auto token = net::load_token_file(options.robot_token_file);
      if (!token) return token.error();
      robot_options.token = *token;
    }
    opened.robot = std::make_unique<net::RobotClient>(robot_options);
    opened.robot->start();
    sim.scene_state = [client = opened.robot.get()]() -> std::optional<vision::SceneState> {
      auto sample = client->latest_state();
      if (!sample) return std::nullopt;
      return vision::SceneState{sample->state.q, sample->state.gripper,
                                sample->capture_client_ns()};
    };
  }
  auto created = sim::SimRigSource::create(std::move(sim));
  if (!created) return created.error();
  opened.source = std::move(*created);
  return Status::Ok();
}

}  // namespace

Result<VisionSource> open_vision_source(const VisionSourceOptions& options) {
  if (!options.robot_server.empty() && options.kind != "sim") {
    return Error{"robot_server is for the sim source (the simulated rig follows the robot)"};
  }
  VisionSource opened;
  if (options.kind == "sim") {
    if (Status s = open_sim(options, opened); !s) return s.error();
  } else if (options.kind == "files") {
    if (options.left.empty() || options.right.empty()) {
      return Error{"the files source needs a left and a right file"};
    }
    vision::VideoFileSourceOptions files{options.left, options.right, options.fps, 0, 0};
    if (options.size) files.width = options.size->width, files.height = options.size->height;
    auto file_source = vision::open_video_file_pair(files);
    if (!file_source) return file_source.error();
    opened.source = std::move(*file_source);
  } else if (options.kind == "v4l2") {
    vision::CameraSourceOptions cameras;
    cameras.left_index = options.left_camera;
    cameras.right_index = options.right_camera;
    if (options.size) cameras.width = options.size->width, cameras.height = options.size->height;
    if (options.fps > 0) cameras.fps = options.fps;
    auto camera_source = vision::open_camera_pair(cameras);
    if (!camera_source) return camera_source.error();
    opened.source = std::move(*camera_source);
  } else if (options.kind == "synthetic") {
    vision::SyntheticSourceOptions synthetic;
    if (options.size) {
      synthetic.width = options.size->width, synthetic.height = options.size->height;
    }
    if (options.fps > 0) synthetic.fps = options.fps;
    synthetic.frame_code = options.frame_code;
    auto created = vision::SyntheticSource::create(synthetic);
    if (!created) return created.error();
    opened.source = std::move(*created);
  } else if (options.kind == "ros" && options.open_ros) {
    if (options.left.empty() || options.right.empty()) {
      return Error{"the ros source needs a left and a right image topic"};
    }
    auto ros = options.open_ros(options);
    if (!ros) return ros.error();
    opened = std::move(*ros);
    if (options.size) {
      opened.warnings.emplace_back(
          "the size is ignored for the ros source (the camera topics set it); clients may ask "
          "for a scaled stream");
    }
  } else {
    return Error{"source '" + options.kind + "' is not one of sim, files, v4l2, synthetic" +
                 (options.open_ros ? ", ros" : "")};
  }
  return opened;
}

}  // namespace telear::lab
