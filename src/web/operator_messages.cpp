#include "telear/web/operator_messages.hpp"

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "telear/render/camera_projection.hpp"
#include "telear/vision/distortion_maps.hpp"

namespace telear::web {

namespace {

using nlohmann::json;

// 7 significant digits: what the page's float32 holds, in a third of the text of a double's.
double round7(double value) {
  if (value == 0.0 || !std::isfinite(value)) return value;
  const double scale =
      std::pow(10.0, 6 - static_cast<int>(std::floor(std::log10(std::fabs(value)))));
  return std::round(value * scale) / scale;
}

std::vector<double> matrix_values(const Eigen::Matrix4d& m) {
  std::vector<double> out;
  append_matrix(out, m);
  return out;
}

template <class T>
std::string bytes_of(const std::vector<T>& values) {
  return base64_encode(
      std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)));
}

json mesh_json(const std::string& name, const core::Mesh& mesh) {
  return {{"name", name},
          {"vertices", bytes_of(mesh.vertices)},
          {"triangles", bytes_of(mesh.triangles)},
          {"lines", bytes_of(mesh.lines)}};
}

void put_u32(std::string& out, std::size_t offset, std::uint32_t value) {
  // Little-endian on the wire whatever this machine's order.
  for (int i = 0; i < 4; ++i) out[offset + i] = static_cast<char>((value >> (8 * i)) & 0xFFu);
}

double ns_to_ms(std::int64_t ns) {
  return static_cast<double>(ns) / 1e6;
}

}  // namespace

void append_matrix(std::vector<double>& out, const Eigen::Matrix4d& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out.push_back(round7(m(r, c)));
}

void append_matrix(std::vector<double>& out, const Eigen::Matrix4f& m) {
  append_matrix(out, Eigen::Matrix4d(m.cast<double>()));
}

std::string base64_encode(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t n = (static_cast<std::uint8_t>(bytes[i]) << 16) |
                            (static_cast<std::uint8_t>(bytes[i + 1]) << 8) |
                            static_cast<std::uint8_t>(bytes[i + 2]);
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += kAlphabet[(n >> 6) & 63];
    out += kAlphabet[n & 63];
  }
  if (i < bytes.size()) {
    std::uint32_t n = static_cast<std::uint8_t>(bytes[i]) << 16;
    const bool two = i + 1 < bytes.size();
    if (two) n |= static_cast<std::uint8_t>(bytes[i + 1]) << 8;
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += two ? kAlphabet[(n >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

EyeProjection eye_projection(const std::string& name, const vision::CameraModel& camera) {
  EyeProjection eye;
  eye.name = name;
  eye.width = camera.width;
  eye.height = camera.height;
  const render::PinholeProjection full = render::PinholeProjection::from_camera(camera);
  eye.projection = render::gl_projection(full);
  eye.view = render::gl_view(camera.T_cam_base);
  const vision::RawToPinholeLut lut = vision::compute_raw_to_pinhole_lut(camera);
  eye.region = render::raw_overlay_region(lut, camera.width, camera.height);
  eye.region_projection = render::gl_projection(
      full.region(eye.region.x0, eye.region.y0, eye.region.width, eye.region.height));
  eye.lut = render::raw_overlay_lut(lut);
  return eye;
}

std::string hello_message(const core::RobotModel& model, bool embedded) {
  json names = json::array();
  for (const auto& joint : model.joints()) names.push_back(joint.name);
  return json{{"type", "hello"},
              {"robot", model.name()},
              {"dof", model.dof()},
              {"joint_names", names},
              {"embedded", embedded}}
      .dump();
}

std::string connection_message(std::string_view state, const std::string& reason) {
  json message{{"type", "connection"}, {"state", state}};
  if (!reason.empty()) message["reason"] = reason;
  return message.dump();
}

std::string model_message(const core::ArmBody& body,
                          const std::vector<render::SceneObject>& objects) {
  json parts = json::array();
  for (const core::BodyPart& part : body.parts) {
    json p = mesh_json(part.name, part.mesh);
    p["link"] = part.link;
    parts.push_back(std::move(p));
  }
  json scene = json::array();
  for (const render::SceneObject& object : objects) {
    json o = mesh_json(object.name, object.mesh);
    o["pose"] = matrix_values(object.T_base_object.matrix().cast<double>());
    scene.push_back(std::move(o));
  }
  return json{{"type", "model"}, {"parts", parts}, {"objects", scene}}.dump();
}

std::string cameras_message(const std::vector<EyeProjection>& eyes) {
  json list = json::array();
  for (const EyeProjection& eye : eyes) {
    list.push_back({{"name", eye.name},
                    {"projection", matrix_values(eye.projection)},
                    {"view", matrix_values(eye.view)},
                    {"region",
                     {{"x0", eye.region.x0},
                      {"y0", eye.region.y0},
                      {"width", eye.region.width},
                      {"height", eye.region.height}}},
                    {"region_projection", matrix_values(eye.region_projection)}});
  }
  const int width = eyes.empty() ? 0 : eyes.front().width;
  const int height = eyes.empty() ? 0 : eyes.front().height;
  return json{{"type", "cameras"}, {"width", width}, {"height", height}, {"eyes", list}}.dump();
}

std::string result_message(std::int64_t id, bool ok, const std::string& message) {
  return json{{"type", "result"}, {"id", id}, {"ok", ok}, {"message", message}}.dump();
}

std::string pong_message(std::int64_t id, double page_ms, double server_ms) {
  return json{{"type", "pong"}, {"id", id}, {"page_ms", page_ms}, {"server_ms", server_ms}}.dump();
}

std::string lut_message(int eye, const EyeProjection& projection) {
  const std::size_t payload = projection.lut.size() * sizeof(float);
  std::string out(12 + payload, '\0');
  out[0] = static_cast<char>(BinaryKind::kLookUpTable);
  out[1] = static_cast<char>(eye);
  put_u32(out, 4, static_cast<std::uint32_t>(projection.width));
  put_u32(out, 8, static_cast<std::uint32_t>(projection.height));
  std::memcpy(out.data() + 12, projection.lut.data(), payload);
  return out;
}

std::string video_frame_message(const net::ReceivedStereoFrame& frame, std::int64_t sent_ns) {
  const std::string& left = frame.jpeg_left != nullptr ? *frame.jpeg_left : std::string();
  const std::string& right = frame.jpeg_right != nullptr ? *frame.jpeg_right : std::string();
  const std::string header = json{
      {"frame_id", frame.frame_id},
      {"capture_ms_left", ns_to_ms(frame.capture_ns_left)},
      {"capture_ms_right", ns_to_ms(frame.capture_ns_right)},
      {"received_ms", ns_to_ms(frame.receive_ns)},
      {"sent_ms", ns_to_ms(sent_ns)},
      {"width", frame.width_left},
      {"height", frame.height_left},
      {"left_bytes", left.size()},
      {"right_bytes",
       right.size()}}.dump();
  std::string out(8, '\0');
  out[0] = static_cast<char>(BinaryKind::kVideoFrame);
  put_u32(out, 4, static_cast<std::uint32_t>(header.size()));
  out.reserve(8 + header.size() + left.size() + right.size());
  out += header;
  out += left;
  out += right;
  return out;
}

}  // namespace telear::web
