#include "telear/render/overlay.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "telear/vision/distortion_maps.hpp"

namespace telear::render {
namespace {

// One triangle covering the viewport; every fragment shader below works from gl_FragCoord.
const char* const kFullScreenVertex = R"glsl(#version 330 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)glsl";

// Undistorted mode's background: output pixel (i, j) of GL's bottom-up framebuffer is OpenCV
// pixel (i, H - 1 - j); its map texel holds the raw-image position to sample, in OpenCV
// pixels. VideoBackground's texture holds the frame as RGB with GL's bottom-up rows, so raw
// position (u, v) is texture coordinate ((u + 0.5) / W, 1 - (v + 0.5) / H). Outside the raw
// image: the clear colour.
const char* const kRemapFragment = R"glsl(#version 330 core
uniform sampler2D u_frame;
uniform sampler2D u_map;
uniform vec3 u_clear_colour;
out vec4 frag_colour;
void main() {
  ivec2 size = textureSize(u_frame, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 raw = texelFetch(u_map, ivec2(p.x, size.y - 1 - p.y), 0).rg;
  if (raw.x < -0.5 || raw.y < -0.5 || raw.x > float(size.x) - 0.5 ||
      raw.y > float(size.y) - 0.5) {
    frag_colour = vec4(u_clear_colour, 1.0);
    return;
  }
  vec2 st = vec2((raw.x + 0.5) / float(size.x), 1.0 - (raw.y + 0.5) / float(size.y));
  frag_colour = vec4(texture(u_frame, st).rgb, 1.0);
}
)glsl";

// Raw mode's warp: raw pixel (i, H - 1 - j) -> its pinhole position q (OpenCV pixels of the
// camera's plane) -> position q - origin in the pinhole region, whose colour texture is GL
// bottom-up (texel row 0 = the region's bottom row). The region holds premultiplied colour.
const char* const kWarpFragment = R"glsl(#version 330 core
uniform sampler2D u_scene;
uniform sampler2D u_lut;
uniform vec2 u_origin;
out vec4 frag_colour;
void main() {
  ivec2 lut_size = textureSize(u_lut, 0);
  vec2 region = vec2(textureSize(u_scene, 0));
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 q = texelFetch(u_lut, ivec2(p.x, lut_size.y - 1 - p.y), 0).rg - u_origin;
  if (q.x < -0.5 || q.y < -0.5 || q.x > region.x - 0.5 || q.y > region.y - 0.5) discard;
  frag_colour = texture(u_scene, vec2((q.x + 0.5) / region.x, 1.0 - (q.y + 0.5) / region.y));
}
)glsl";

Texture upload_rg32f(int width, int height, const std::vector<float>& rg) {
  Texture t = Texture::create_2d(width, height, GL_RG32F);
  t.bind(GL_TEXTURE0);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  t.upload(GL_RG, GL_FLOAT, rg.data());
  return t;
}

}  // namespace

RawOverlayRegion raw_overlay_region(const vision::RawToPinholeLut& lut, int width, int height) {
  const double W = width;
  const double H = height;
  const double min_u = std::max(std::min(lut.min_u, 0.0), -W);
  const double min_v = std::max(std::min(lut.min_v, 0.0), -H);
  const double max_u = std::min(std::max(lut.max_u, W - 1.0), 2.0 * W - 1.0);
  const double max_v = std::min(std::max(lut.max_v, H - 1.0), 2.0 * H - 1.0);
  RawOverlayRegion region;
  region.x0 = static_cast<int>(std::floor(min_u)) - 2;
  region.y0 = static_cast<int>(std::floor(min_v)) - 2;
  region.width = static_cast<int>(std::ceil(max_u)) + 2 - region.x0 + 1;
  region.height = static_cast<int>(std::ceil(max_v)) + 2 - region.y0 + 1;
  return region;
}

std::vector<float> raw_overlay_lut(const vision::RawToPinholeLut& lut) {
  const int W = lut.pinhole_uv.cols;
  const int H = lut.pinhole_uv.rows;
  std::vector<float> rg(static_cast<size_t>(W) * H * 2);
  for (int v = 0; v < H; ++v) {
    for (int u = 0; u < W; ++u) {
      const cv::Vec2f q = lut.pinhole_uv.at<cv::Vec2f>(v, u);
      const size_t i = (static_cast<size_t>(v) * W + u) * 2;
      rg[i] = std::isnan(q[0]) ? kNoPinholeRay : q[0];
      rg[i + 1] = std::isnan(q[1]) ? kNoPinholeRay : q[1];
    }
  }
  return rg;
}

Result<Overlay> Overlay::create(const vision::CameraModel& camera, const OverlayOptions& options) {
  if (Status valid = vision::validate_camera(camera); !valid) {
    return Error{"overlay: " + valid.error().message};
  }
  Overlay o;
  o.camera_ = camera;
  o.options_ = options;
  const int W = camera.width, H = camera.height;
  auto background = VideoBackground::create(W, H);
  if (!background) return background.error();
  o.background_ = std::move(background.value());
  o.vao_ = VertexArray::create();
  const PinholeProjection full =
      PinholeProjection::from_camera(camera, options.near_m, options.far_m);

  if (options.mode == OverlayMode::kUndistorted) {
    const vision::UndistortMaps maps = vision::compute_undistort_maps(camera);
    std::vector<float> rg(static_cast<size_t>(W) * H * 2);
    for (int v = 0; v < H; ++v) {
      for (int u = 0; u < W; ++u) {
        const size_t i = (static_cast<size_t>(v) * W + u) * 2;
        rg[i] = maps.map_x.at<float>(v, u);
        rg[i + 1] = maps.map_y.at<float>(v, u);
      }
    }
    o.undistort_map_ = upload_rg32f(W, H, rg);
    auto program = Program::link(kFullScreenVertex, kRemapFragment, "overlay undistort");
    if (!program) return program.error();
    o.remap_program_ = std::move(program.value());
    o.remap_program_.use();
    glUniform1i(o.remap_program_.uniform_location("u_frame"), 0);
    glUniform1i(o.remap_program_.uniform_location("u_map"), 1);
    glUniform3fv(o.remap_program_.uniform_location("u_clear_colour"), 1,
                 options.clear_colour.data());
    o.scene_projection_ = full;
    return o;
  }

  // kRaw: the scene into a pinhole image around the raw one, warped through the look-up table.
  const vision::RawToPinholeLut lut = vision::compute_raw_to_pinhole_lut(camera);
  const RawOverlayRegion region = raw_overlay_region(lut, W, H);
  const int x0 = region.x0;
  const int y0 = region.y0;
  o.region_origin_ = {x0, y0};
  o.scene_projection_ = full.region(x0, y0, region.width, region.height);
  auto pinhole = OffscreenTarget::create(region.width, region.height, options.samples);
  if (!pinhole) return Error{"overlay: pinhole image: " + pinhole.error().message};
  o.pinhole_ = std::move(pinhole.value());
  const std::vector<float> rg = raw_overlay_lut(lut);
  o.lut_ = upload_rg32f(W, H, rg);
  auto program = Program::link(kFullScreenVertex, kWarpFragment, "overlay warp");
  if (!program) return program.error();
  o.warp_program_ = std::move(program.value());
  o.warp_program_.use();
  glUniform1i(o.warp_program_.uniform_location("u_scene"), 0);
  glUniform1i(o.warp_program_.uniform_location("u_lut"), 1);
  glUniform2f(o.warp_program_.uniform_location("u_origin"), static_cast<float>(x0),
              static_cast<float>(y0));
  return o;
}

void Overlay::upload_frame(const std::uint8_t* pixels, ChannelOrder order) {
  background_.upload(pixels, order);
  has_frame_ = true;
}

void Overlay::upload_planes(const core::YCbCrImage& planes) {
  background_.upload_planes(planes);
  has_frame_ = true;
}

void Overlay::draw_undistorted_background() const {
  remap_program_.use();
  background_.texture().bind(GL_TEXTURE0);
  undistort_map_.bind(GL_TEXTURE1);
  glActiveTexture(GL_TEXTURE0);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  vao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
}

void Overlay::render(const OffscreenTarget& target, const SceneDrawer& draw_scene) const {
  assert(target.width() == camera_.width && target.height() == camera_.height &&
         "Overlay::render(): the target must have the camera's image size");
  const Eigen::Matrix4f projection = gl_projection(scene_projection_).cast<float>();
  const Eigen::Matrix4f view = gl_view(camera_.T_cam_base).cast<float>();
  const Eigen::Vector3f& clear = options_.clear_colour;

  if (options_.mode == OverlayMode::kUndistorted) {
    target.clear(clear.x(), clear.y(), clear.z(), 1.0f);
    if (has_frame_) draw_undistorted_background();
    target.bind();
    if (draw_scene) draw_scene(projection, view);
    return;
  }

  // kRaw: the scene into the transparent pinhole region, then warped over the raw frame.
  pinhole_.clear(0.0f, 0.0f, 0.0f, 0.0f);
  pinhole_.bind();
  if (draw_scene) draw_scene(projection, view);
  pinhole_.resolve();
  target.clear(clear.x(), clear.y(), clear.z(), 1.0f);
  if (has_frame_) background_.draw();
  target.bind();
  warp_program_.use();
  pinhole_.colour_texture().bind(GL_TEXTURE0);
  lut_.bind(GL_TEXTURE1);
  glActiveTexture(GL_TEXTURE0);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  vao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace telear::render
