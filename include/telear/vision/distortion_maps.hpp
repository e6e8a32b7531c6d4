#pragma once
// The two pixel maps that let telear honour lens distortion, each computed once per camera
// (docs/cameras.md, "Overlay modes").
//
// Undistort maps (the *undistorted* overlay mode): the output is the image an ideal pinhole
// camera with the same K would see. For each output pixel (u, v), the raw-image position of
// the same ray:
//     (map_x, map_y)(v, u) = K distort(K^-1 (u, v))
// computed with cv::initUndistortRectifyMap (R = I, new camera matrix = K) when the skew is
// zero -- OpenCV ignores K(0,1) -- and from CameraModel's own formulas otherwise. Output
// pixels whose ray lies beyond the lens model's monotonic radius (where the polynomial folds
// back and the remapped image would show a mirrored copy) get -1, i.e. no source pixel.
//
// Raw-to-pinhole look-up table (the *raw* overlay mode): the arm is drawn with K as a
// pinhole image, then warped into the distorted image. For each raw pixel (u, v), where the
// pinhole image shows the same ray:
//     pinhole_uv(v, u) = K undistort(K^-1 (u, v))
// by Newton's method (CameraModel::undistort), NaN where the model is not invertible.
//
// Buffers are cv::Mat of height x width (the camera's image size): map_x and map_y CV_32FC1,
// pinhole_uv CV_32FC2 (u, v). Coordinates are OpenCV pixel coordinates (pixel centres at
// integers).

#include <opencv2/core.hpp>

#include "telear/vision/camera_model.hpp"

namespace telear::vision {

struct UndistortMaps {
  cv::Mat map_x;  // CV_32FC1, height x width
  cv::Mat map_y;  // CV_32FC1, height x width
};

UndistortMaps compute_undistort_maps(const CameraModel& camera);

// cv::remap with the maps, bilinear, black outside the raw image.
cv::Mat undistort_image(const cv::Mat& raw, const UndistortMaps& maps);

struct RawToPinholeLut {
  cv::Mat pinhole_uv;  // CV_32FC2, height x width; NaN where not invertible
  // Bounds of the finite entries (pixels); with barrel distortion they extend beyond the
  // image, which is why the raw overlay mode draws its pinhole image with a margin.
  double min_u = 0.0, min_v = 0.0, max_u = 0.0, max_v = 0.0;
  int invalid_count = 0;  // entries set to NaN
};

RawToPinholeLut compute_raw_to_pinhole_lut(const CameraModel& camera);

}  // namespace telear::vision
