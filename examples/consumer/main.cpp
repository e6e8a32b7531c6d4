// telear_consumer: the smallest program built on the installed telear package
// (examples/consumer/CMakeLists.txt, docs/install.md). It
//   1. loads the shipped PUMA 560 (DATA/robots/puma560.yaml) through telear::core and prints
//      the tool pose (forward kinematics) at its named configuration "qr";
//   2. loads the shipped stereo camera file (DATA/cameras/puma560_stereo.yaml) through
//      telear::vision and projects the tool position into the left image;
//   3. runs a display-mode decision (telear::session) and constructs a robot client
//      (telear::net, gRPC; lazy: it connects to nothing), so both libraries and their
//      dependencies link.
// Usage: telear_consumer [DATA_DIR]   (default: the installed package's share/telear/data).
// Exit status 0 on success, 1 with a message on any failure.

#include <iostream>
#include <optional>
#include <string>

#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/version.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/session/display_mode.hpp"
#include "telear/vision/camera_file.hpp"

namespace {

int fail(const std::string& message) {
  std::cerr << "telear_consumer: error: " << message << "\n";
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace telear;
  const std::string data_dir = argc > 1 ? argv[1] : CONSUMER_DATA_DIR;
  std::cout << "telear " << core::version_string() << ", data " << data_dir << "\n";

  // core: the robot and its forward kinematics at a named configuration.
  auto model = core::load_robot(data_dir + "/robots/puma560.yaml");
  if (!model) return fail(model.error().message);
  const auto q_rad = (*model)->named_configuration("qr");
  if (!q_rad) return fail("robot '" + (*model)->name() + "' has no named configuration 'qr'");
  core::KinematicsData data(**model);
  core::forward_kinematics(**model, data, *q_rad);
  const Eigen::Vector3d p_base_tool_m = data.T_base_tool.translation();
  std::cout << (*model)->name() << " (" << (*model)->dof() << " joints) at qr: tool at ["
            << p_base_tool_m.transpose() << "] m\n";
  if (!p_base_tool_m.allFinite() || p_base_tool_m.norm() < 0.1) {
    return fail("forward kinematics gave an implausible tool position");
  }

  // vision: the shipped stereo camera pair; the tool seen by the left camera.
  const std::string camera_path = data_dir + "/cameras/puma560_stereo.yaml";
  auto cameras = vision::load_camera_file(camera_path);
  if (!cameras) return fail(cameras.error().message);
  if (!cameras->is_stereo()) return fail("camera file '" + camera_path + "' is not a stereo pair");
  const auto uv_px = cameras->left.project(p_base_tool_m);
  if (!uv_px) return fail("the tool at qr is behind the left camera of '" + camera_path + "'");
  std::cout << "left camera sees the tool at pixel [" << uv_px->transpose() << "]\n";

  // session: with no video yet, the display is the VR view.
  session::DisplayModeSelector selector;
  const auto mode = selector.update(0.0, std::nullopt).mode;
  std::cout << "display mode without video: " << session::to_string(mode) << "\n";
  if (mode != session::DisplayMode::kVR) return fail("expected VR without video");

  // net: a robot client (gRPC channel created lazily; not started, so nothing is contacted).
  net::RobotClientOptions client_options;
  client_options.address = "127.0.0.1:1";
  client_options.client_name = "telear-consumer";
  net::RobotClient client(client_options);
  std::cout << "robot client for " << client.options().address
            << (client.connected() ? " connected" : " not connected (not started)") << "\n";
  return 0;
}
