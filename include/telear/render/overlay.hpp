#pragma once
// The arm (or any scene) superimposed on a camera's video frame, honouring lens distortion,
// so that a point of the scene lands where cv::projectPoints (with the distortion) puts it
// in the video. Two modes (docs/cameras.md):
//
//   kUndistorted  the frame is remapped into an ideal pinhole image with the same K (maps
//                 from cv::initUndistortRectifyMap, computed once, applied on the GPU: one
//                 texture fetch through an RG32F map texture per pixel), then the scene is
//                 drawn on top with K (telear/render/camera_projection.hpp). The output is the
//                 undistorted image.
//   kRaw          the frame is shown as it came from the camera; the scene is drawn with K
//                 into a pinhole image (an FBO covering the pinhole pixel range of every raw
//                 pixel, a margin around the image with barrel distortion), then warped into
//                 the distorted image through a raw-to-pinhole look-up texture (computed
//                 once, telear/vision/distortion_maps.hpp) and composited over the frame with
//                 premultiplied alpha. The output is the raw image.
//
// Without distortion both modes give the same picture. A frame is width x height x 3 bytes
// (the camera's image size), RGB or BGR, top row first. The scene is drawn by a callback
// given the projection and view matrices (conventions: telear/render/view_math.hpp), into the bound
// framebuffer with its viewport set and the depth buffer cleared; it may draw an ArmRenderer,
// scene objects, PointMarkers.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/render/camera_projection.hpp"
#include "telear/render/gl_objects.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/video_background.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/distortion_maps.hpp"

namespace telear::render {

enum class OverlayMode { kUndistorted, kRaw };

struct OverlayOptions {
  OverlayMode mode = OverlayMode::kRaw;
  double near_m = 0.05;  // clip planes along z_cam
  double far_m = 50.0;
  // Colour behind everything when no frame has been uploaded (and outside the undistorted
  // image's valid area).
  Eigen::Vector3f clear_colour = Eigen::Vector3f::Zero();
  // kRaw: samples per pixel of the scene's pinhole image (OffscreenTarget, multisampled when
  // > 1: anti-aliased edges). kUndistorted draws into the caller's target, which chooses.
  int samples = 1;
};

// The raw mode's pinhole image for a camera (x0, y0: the pixel of the camera's plane its
// top-left pixel shows): every raw pixel's pinhole position, plus 2 pixels for the bilinear
// footprint, and at least the image itself; at most one image size of margin on each side
// (rays beyond it, at the corners of extreme lenses, are not drawn). And the look-up table as
// the warp reads it: per raw pixel, top row first, its pinhole position (u, v), or
// kNoPinholeRay where the lens model has no ray. The browser operator (telear web) draws with
// the same two.
struct RawOverlayRegion {
  int x0 = 0, y0 = 0;
  int width = 0, height = 0;
};
inline constexpr float kNoPinholeRay = -1.0e9f;
RawOverlayRegion raw_overlay_region(const vision::RawToPinholeLut& lut, int width, int height);
std::vector<float> raw_overlay_lut(const vision::RawToPinholeLut& lut);

using SceneDrawer =
    std::function<void(const Eigen::Matrix4f& projection, const Eigen::Matrix4f& T_view_base)>;

class Overlay {
 public:
  Overlay() = default;
  // Computes the maps (vision), uploads them and builds the programs. Needs a current
  // context. Errors: invalid camera, shader or framebuffer failure.
  static Result<Overlay> create(const vision::CameraModel& camera,
                                const OverlayOptions& options = {});

  const vision::CameraModel& camera() const { return camera_; }
  OverlayMode mode() const { return options_.mode; }
  // The projection the scene is drawn with: K over the image (undistorted mode) or K over
  // the pinhole region (raw mode; region_origin() is its top-left pixel).
  const PinholeProjection& scene_projection() const { return scene_projection_; }
  Eigen::Vector2i region_origin() const { return region_origin_; }

  // Uploads one frame (camera().width x camera().height x 3 bytes, top row first).
  void upload_frame(const std::uint8_t* pixels, ChannelOrder order = ChannelOrder::kBgr);
  // The same frame as a decoded JPEG's planes (VideoBackground::upload_planes).
  void upload_planes(const core::YCbCrImage& planes);
  // Forgets the frame: render() shows the clear colour behind the scene.
  void clear_frame() { has_frame_ = false; }

  // Draws the composed view into `target` (the camera's image size).
  void render(const OffscreenTarget& target, const SceneDrawer& draw_scene) const;

 private:
  void draw_undistorted_background() const;

  vision::CameraModel camera_;
  OverlayOptions options_;
  PinholeProjection scene_projection_;
  Eigen::Vector2i region_origin_ = Eigen::Vector2i::Zero();
  VideoBackground background_;
  bool has_frame_ = false;
  VertexArray vao_;  // empty: full-screen triangles come from gl_VertexID
  // kUndistorted
  Texture undistort_map_;  // RG32F, raw-image position per output pixel, row 0 = image top
  Program remap_program_;
  // kRaw
  Texture lut_;  // RG32F, pinhole position per raw pixel, row 0 = image top
  OffscreenTarget pinhole_;
  Program warp_program_;
};

}  // namespace telear::render
