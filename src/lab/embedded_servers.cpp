#include "telear/lab/embedded_servers.hpp"

#include <filesystem>
#include <system_error>

#include "telear/core/robot_loader.hpp"
#include "telear/core/workspace.hpp"
#include "telear/net/random_token.hpp"
#include "telear/sim/rig_robot.hpp"
#include "telear/sim/sim_rig_source.hpp"
#include "telear/sim/stereo_rig.hpp"

namespace telear::lab {

Status serve_robot(EmbeddedServersOptions& options, const core::RobotDescription& description) {
  options.urdf = core::urdf_text_for_clients(description);
  options.tip_link = description.tip_link;
  // The robot server is the collision authority in the robot's shipped workspace, as `telear
  // robot-server --workspace` is (without one, nothing: self-collision alone would refuse the
  // PUMA's everyday poses, docs/collision.md). The graspable box is no obstacle to it: the
  // guard carries it from the grasp, as the session's validation does.
  std::error_code ec;
  if (options.workspace_file.empty()) {
    const std::string workspace = core::default_workspace_file(description.name);
    if (std::filesystem::exists(workspace, ec)) options.workspace_file = workspace;
  }
  if (!options.workspace_file.empty() && !options.robot_description) {
    options.robot_description = description;
  }
  if (!options.rig.empty()) return Status::Ok();
  const std::string rig = sim::default_rig_file(description.name);
  if (!std::filesystem::exists(rig, ec)) {
    return Error{"the robot '" + description.name + "' has no simulated rig " + rig +
                 " (shipped: puma560, ur6, arm7; docs/simulation.md says how to add one)"};
  }
  options.rig = rig;
  return Status::Ok();
}

EmbeddedServers::~EmbeddedServers() {
  stop();
}

void EmbeddedServers::stop() {
  // Downstream first: the vision server reads the follower, the follower reads the robot.
  if (vision_) vision_->stop();
  if (follower_) follower_->stop();
  if (robot_) robot_->shutdown();
}

Result<std::unique_ptr<EmbeddedServers>> EmbeddedServers::create(core::RobotModelPtr model,
                                                                 EmbeddedServersOptions options) {
  std::unique_ptr<EmbeddedServers> servers(new EmbeddedServers());
  servers->token_ = options.token.empty() ? net::random_token(16) : options.token;

  sim::SimRobotDriverOptions driver_options;
  driver_options.robot.initial_q = options.initial_q;
  if (driver_options.robot.initial_q.size() == 0) {
    driver_options.robot.initial_q = sim::rest_configuration(*model);
  }
  driver_options.urdf = options.urdf;
  driver_options.tip_link = options.tip_link;
  auto driver = sim::SimRobotDriver::create(model, driver_options);
  if (!driver) return Error{"embedded robot server: " + driver.error().message};
  servers->driver_ = driver->get();

  net::RobotServerOptions robot_options;
  robot_options.listen_address = "127.0.0.1:0";
  robot_options.token = servers->token_;
  robot_options.robot_description = options.robot_description;
  robot_options.workspace_file = options.workspace_file;
  auto robot = net::RobotServer::create(std::move(*driver), robot_options);
  if (!robot) return Error{"embedded robot server: " + robot.error().message};
  servers->robot_ = std::move(*robot);

  net::RobotClientOptions follower_options;
  follower_options.address = servers->robot_->address();
  follower_options.token = servers->token_;
  follower_options.client_name = "vision-server-rig";
  follower_options.state_rate_hz = 100.0;
  servers->follower_ = std::make_unique<net::RobotClient>(follower_options);
  servers->follower_->start();

  sim::SimRigSourceOptions rig_options;
  rig_options.rig = options.rig.empty() ? sim::default_rig_file() : options.rig;
  rig_options.fps = options.fps;
  rig_options.supersample = options.supersample;
  rig_options.multisample = options.multisample;
  rig_options.noise_sigma = options.noise_sigma;
  rig_options.seed = options.seed;
  rig_options.frame_code = options.frame_code;
  net::RobotClient* follower = servers->follower_.get();
  rig_options.scene_state = [follower]() -> std::optional<vision::SceneState> {
    const auto sample = follower->latest_state();
    if (!sample) return std::nullopt;
    return vision::SceneState{sample->state.q, sample->state.gripper, sample->capture_ns};
  };
  auto source = sim::SimRigSource::create(rig_options);
  if (!source) return Error{"embedded vision server: " + source.error().message};
  servers->rig_cameras_ = (*source)->true_cameras();

  net::VisionServerOptions vision_options;
  vision_options.listen_address = "127.0.0.1:0";
  vision_options.source = std::move(*source);
  vision_options.calibration_file = options.calibration_file;
  // Reading the video needs the token too, as on any server started by hand (issue 25).
  vision_options.token = servers->token_;
  auto vision = net::VisionServer::create(std::move(vision_options));
  if (!vision) return Error{"embedded vision server: " + vision.error().message};
  servers->vision_ = std::move(*vision);
  return servers;
}

}  // namespace telear::lab
