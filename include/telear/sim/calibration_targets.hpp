#pragma once
// Calibration targets placed in the simulated scene, and the ArUco marker on the gripper.
// Both are flat meshes of exactly-placed coloured quads and polygons (the "texture" is
// geometry, so its edges and corners are where the math says, to float precision; the scene
// renderer anti-aliases by supersampling).
//
// Target frame: telear/vision/calibration_pattern.hpp's -- the pattern's points at z = 0 in
// detection order, x along a row, y down the columns; the printed face is seen from -z (z
// points into the board, away from a camera that sees the pattern the right way round).
//   chessboard  (cols + 1) x (rows + 1) squares of side s, square (i, j), i = -1..cols - 1,
//               j = -1..rows - 1, covering [i s, (i + 1) s] x [j s, (j + 1) s], black when
//               i + j is even, inside a white margin of `margin_squares` squares.
//   circles     OpenCV's asymmetric grid: dark discs of radius 0.3 s (96-gon, whose centroid
//               is the centre) at ((2 c + r mod 2) s, r s, 0) on a white plate 0.2 mm behind
//               (z = +0.0002), so the discs never z-fight with it.
//   charuco     the layout of telear/vision/charuco_board.hpp (OpenCV's board): its black
//               squares and the black cells of its markers at z = 0, on a white plate 0.2 mm
//               behind that covers the board and a white margin of `margin_squares` squares.
//
// The scene renderer draws the mesh with OpenGL (telear sim capture). render_target_image()
// draws a target alone on a grey background on the CPU, for tests that need many views fast
// and views partly out of frame: each pixel averages supersample^2 rays through the true
// camera (its distortion included) to the target plane and the target's reflectance there.
//
// ArUco marker (DICT_4X4_50, OpenCV 4.6's cv::aruco): the 6 x 6-cell marker (4 x 4 bits and a
// black border) inside a white quiet zone of one cell, on a thin backing plate. Marker frame
// (OpenCV's aruco convention): origin at the marker's centre, x to the right and y up as the
// marker image is printed, z out of the face towards the viewer; black side L. Corner k, in
// the order cv::aruco::detectMarkers returns them (top-left, top-right, bottom-right,
// bottom-left of the printed image):  (-L/2, L/2, 0), (L/2, L/2, 0), (L/2, -L/2, 0),
// (-L/2, -L/2, 0).

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "telear/core/marker_mount.hpp"
#include "telear/core/mesh.hpp"
#include "telear/core/result.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/charuco_board.hpp"

namespace telear::sim {

struct CalibrationTarget {
  vision::CalibrationPattern pattern;
  core::Mesh mesh;                                        // target frame
  std::vector<Eigen::Vector3d> points_target;             // pattern points, detection order
  Eigen::Vector2d outline_min = Eigen::Vector2d::Zero();  // the board's extent in x, y
  Eigen::Vector2d outline_max = Eigen::Vector2d::Zero();
  vision::CharucoLayout charuco;  // charuco: the board's squares and markers
  // Corners of the outline (z = 0), for visibility checks.
  std::array<Eigen::Vector3d, 4> outline_corners() const;
  // Centre of the pattern's points.
  Eigen::Vector3d pattern_centre() const;
  // What the printed face shows at (x, y) of the target frame: 0 black, 1 white, -1 off the
  // target (beyond the outline).
  double reflectance(double x, double y) const;
};

// `pattern` must be valid (parse_calibration_pattern). margin_squares: white border width in
// units of the spacing (chessboard: squares; circles: s).
CalibrationTarget make_calibration_target(const vision::CalibrationPattern& pattern,
                                          double margin_squares = 1.0);

// Grey images of a target seen by one camera, drawn on the CPU (see above).
class TargetImageRenderer {
 public:
  // Precomputes the camera's rays (one undistortion per pixel corner).
  explicit TargetImageRenderer(const vision::CameraModel& camera);

  // An 8-bit grey image of `target` at T_base_target (black 10, white 237 grey levels) on a
  // background of 128; each pixel the mean of supersample x supersample samples (1..8),
  // then Gaussian noise of sigma noise_grey (seeded). Parts outside the image are cut off.
  cv::Mat render(const CalibrationTarget& target, const Eigen::Isometry3d& T_base_target,
                 int supersample = 4, double noise_grey = 1.0, std::uint64_t seed = 1) const;

 private:
  vision::CameraModel camera_;
  // Undistorted normalized coordinates of the pixel corners (u - 0.5, v - 0.5), u = 0..width,
  // v = 0..height; NaN where undistortion fails (beyond the lens model's range).
  cv::Mat rays_;  // CV_64FC2, (height + 1) x (width + 1)
};

// The marker of a mount (include/telear/core/marker_mount.hpp) as geometry.
struct ArucoMarker {
  core::MarkerMount mount;
  core::Mesh mesh;  // flange frame (marker face, quiet zone and backing plate)
  // The four detector corners in the flange frame (order as above).
  std::array<Eigen::Vector3d, 4> corners_flange;
};

// Errors: a dictionary other than DICT_4X4_50, id outside 0..49, side not positive.
Result<ArucoMarker> make_aruco_marker(const core::MarkerMount& mount);

// Poses of a target held in front of the rig for a calibration set, drawn from a seeded
// generator (the same seed gives the same poses). Each pose: the board's outline fills
// 40-70 % of the image width, its centre lies in the middle 40 % of the image, it is turned
// by up to 20 degrees in its plane and tilted by 10..40 degrees about a random in-plane
// axis; it is accepted only when every outline corner and pattern point projects (with the
// true distortion) at least `margin_px` inside both images and the printed face looks
// towards both cameras. Errors: no acceptable pose found (board too large for the rig).
Result<std::vector<Eigen::Isometry3d>> calibration_target_poses(
    const vision::StereoCameraModel& cameras, const Eigen::Isometry3d& T_base_rig,
    const CalibrationTarget& target, int count, std::uint64_t seed, double margin_px = 12.0);

}  // namespace telear::sim
