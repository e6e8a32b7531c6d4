#pragma once
// The embedded default: a simulated robot server and a simulated stereo vision server
// started in this process, on loopback with ephemeral ports, talking real gRPC. `telear demo`
// and `telear console` (with no addresses) run on them, so a newcomer sees the whole system
// without a robot or a camera; the session connects to them exactly as to remote servers.
//
// The vision server's simulated rig follows the robot server's state stream through an
// observer RobotClient (the same path a remote vision server would take), so the "real" arm
// in the video moves with the robot. Both servers take one bearer token, for commands and for
// reading alike (the video too), generated per start (random) unless given.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/robot_server.hpp"
#include "telear/net/vision_server.hpp"
#include "telear/sim/sim_robot_driver.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::lab {

struct EmbeddedServersOptions {
  std::string rig;               // empty: sim::default_rig_file()
  std::string calibration_file;  // served by GetCameraInfo; empty: none
  std::string token;             // empty: a random one
  Eigen::VectorXd initial_q;     // empty: sim::rest_configuration (qr, ready, home or zeros)
  std::string urdf;              // served by GetInfo with tip_link (a client draws the arm)
  std::string tip_link;
  double fps = 30.0;         // the simulated cameras' frame rate
  int supersample = 1;       // the video's anti-aliasing (1 is fastest)
  int multisample = 1;       // MSAA samples per pixel of the video (sim::SceneOptions)
  double noise_sigma = 1.0;  // grey levels
  std::uint64_t seed = 1;
  // Both eyes carry the frame code (telear/vision/frame_code.hpp), so the operator's view
  // measures capture -> shown (the console's status panel, docs/latency.md).
  bool frame_code = true;
  // The robot server's collision authority (net/robot_server.hpp): the robot checked and its
  // workspace (empty: self-collision only); neither: no checks. serve_robot sets both for the
  // robot's shipped workspace.
  std::optional<core::RobotDescription> robot_description;
  std::string workspace_file;
};

// Options that serve this robot: its URDF and tip on GetInfo (so that a client draws the same
// arm); the robot server as the collision authority in its shipped workspace
// (data/workspaces/NAME_table.yaml, unless `workspace_file` is set; none when there is no such
// file), with the description; and, unless `rig` is set, its shipped simulated rig
// (data/rigs/NAME_rig.yaml). An error naming the robot when it has no rig.
Status serve_robot(EmbeddedServersOptions& options, const core::RobotDescription& description);

class EmbeddedServers {
 public:
  static Result<std::unique_ptr<EmbeddedServers>> create(core::RobotModelPtr model,
                                                         EmbeddedServersOptions options = {});
  ~EmbeddedServers();  // stop()
  EmbeddedServers(const EmbeddedServers&) = delete;
  EmbeddedServers& operator=(const EmbeddedServers&) = delete;

  std::string robot_address() const { return robot_->address(); }
  std::string vision_address() const { return vision_->address(); }
  const std::string& token() const { return token_; }
  net::RobotServer& robot_server() { return *robot_; }
  net::VisionServer& vision_server() { return *vision_; }
  sim::SimRobotDriver& driver() { return *driver_; }  // fault injection in tests
  // The simulated rig's TRUE cameras (a stand-in when no registered calibration is given).
  const vision::StereoCameraModel& rig_cameras() const { return rig_cameras_; }

  void stop();

 private:
  EmbeddedServers() = default;
  std::string token_;
  sim::SimRobotDriver* driver_ = nullptr;  // owned by robot_
  std::unique_ptr<net::RobotServer> robot_;
  std::unique_ptr<net::RobotClient> follower_;  // the rig's view of the robot's state
  std::unique_ptr<net::VisionServer> vision_;
  vision::StereoCameraModel rig_cameras_;
};

}  // namespace telear::lab
