#pragma once
// A calibration image set from the simulated stereo rig (docs/simulation.md, "Stereo rig"):
// what `telear sim capture` writes, and the first step of the demo's calibration pipeline
// (include/telear/lab/calibration_pipeline.hpp).
//
// Writes DIR/left_NN.png and DIR/right_NN.png (NN = 00, 01, ...) with the target at varied,
// well-conditioned poses (include/telear/sim/calibration_targets.hpp), rendered per eye with
// the TRUE cameras (distortion, sensor noise of `noise_grey` grey levels, Gaussian sigma), and
// DIR/truth.yaml: the true cameras in the camera-file format (OpenCV FileStorage YAML, left: /
// right:, each with its T_cam_base), the rig's baseline, the pattern, seed, noise, and per view
// the target's pose in the base frame and in the left camera. truth.yaml is written last and
// atomically, so its presence means the set is complete. Needs a current OpenGL context (the
// function creates a headless one). Single-threaded.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::sim {

struct CalibrationCaptureOptions {
  std::string rig_file;  // sim::load_stereo_rig's YAML
  std::string pattern = "chessboard:9x6:0.03";
  int views = 20;          // 1..100
  std::string output_dir;  // created if missing
  std::uint64_t seed = 1;  // poses and sensor noise
  double noise_grey = 1.0;
  int supersample = 4;     // anti-aliasing factor per axis, 1..8
  bool show_scene = true;  // false: the target alone on the background (no robot, floor, table)

  // Errors name the field (as the CLI option) and the violated range.
  Status validate() const;
};

struct CalibrationCapture {
  std::vector<std::string> left_images;  // paths, in view order
  std::vector<std::string> right_images;
  std::string truth_file;  // DIR/truth.yaml
};

// Called after each view is written: index from 1, count, the two file names (no directory).
using CaptureProgress = std::function<void(int view, int views, const std::string& left_name,
                                           const std::string& right_name)>;

// Errors: invalid options, the rig or its robot / body, no OpenGL context, the output
// directory or a file that cannot be written (each naming the path).
Result<CalibrationCapture> capture_calibration_views(const CalibrationCaptureOptions& options,
                                                     const CaptureProgress& progress = {});

}  // namespace telear::sim
