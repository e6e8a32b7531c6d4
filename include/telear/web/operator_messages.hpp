#pragma once
// The messages between the page and `telear web` (docs/web.md, "The wire"): JSON text for the
// model, the cameras, the state and the answers; binary for the video frames and the lens
// look-up tables. Pure functions of their inputs, so the wire is tested without a socket.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/render/overlay.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::web {

// Standard base64 (RFC 4648, with padding) of raw bytes.
std::string base64_encode(std::string_view bytes);

// One eye as the page draws it: the console's projection over the image, the view (T_cam_base)
// and the raw overlay's pinhole region with its projection and look-up table
// (render/overlay.hpp), so that the ghost lands on the video as in the console.
struct EyeProjection {
  std::string name;  // "left", "right"
  int width = 0, height = 0;
  Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  render::RawOverlayRegion region;
  Eigen::Matrix4d region_projection = Eigen::Matrix4d::Identity();
  std::vector<float> lut;  // width x height x (u, v), top row first
};
EyeProjection eye_projection(const std::string& name, const vision::CameraModel& camera);

std::string hello_message(const core::RobotModel& model, bool embedded);
// state: "connecting", "connected", "disconnected" or "refused" (with the reason).
std::string connection_message(std::string_view state, const std::string& reason = {});
std::string model_message(const core::ArmBody& body,
                          const std::vector<render::SceneObject>& objects);
std::string cameras_message(const std::vector<EyeProjection>& eyes);
std::string result_message(std::int64_t id, bool ok, const std::string& message);
std::string pong_message(std::int64_t id, double page_ms, double server_ms);

// Binary kind 2: eye 0 (left) or 1 (right)'s look-up table.
std::string lut_message(int eye, const EyeProjection& projection);
// Binary kind 1: the stereo JPEG pair as received, with its stamps (this machine's monotonic
// clock, ms; `sent_ns` when it was queued for the page).
std::string video_frame_message(const net::ReceivedStereoFrame& frame, std::int64_t sent_ns);

// A binary message's kind byte, for readers (tests): 1 video, 2 look-up table.
enum class BinaryKind : std::uint8_t { kVideoFrame = 1, kLookUpTable = 2 };

// Column-major floats of 4x4 matrices, rounded to 7 significant digits (the page's float32).
void append_matrix(std::vector<double>& out, const Eigen::Matrix4d& m);
void append_matrix(std::vector<double>& out, const Eigen::Matrix4f& m);

}  // namespace telear::web
