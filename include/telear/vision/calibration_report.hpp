#pragma once
// The calibration report: what `telear calibrate --report` writes (JSON) and the summary
// table it prints. docs/calibration.md lists every field; in short:
//
//   kind            "mono" | "stereo"
//   pattern         the pattern spec, e.g. "chessboard:9x6:0.025"
//   image_size      {width, height}
//   views_given     images (mono) or pairs (stereo) given
//   views_used      views that entered the final solution
//   views_rejected  views left out: no pattern, undecodable, wrong size, outlier
//   rms_px          reprojection RMS of the final solution (stereo: both images together)
//   cameras         {"left": ..., "right": ...} (mono: {"camera": ...}); per camera
//                   rms_px, mono_rms_px (stereo: the camera calibrated alone), and
//                   fx fy cx cy alpha_c k1 k2 p1 p2 k3, each {value, std} (1-sigma)
//   stereo          R (3x3 rows), rotation_vector_rad {value, std}, T {value, std},
//                   baseline {value, std}, units, E, F, rectification {R1 R2 P1 P2 Q,
//                   left_roi, right_roi}
//   views           in file order, one object per image or pair: the file name(s), status
//                   "used" | "rejected", rms_px (per image), or reason (rejected)

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/mono_calibration.hpp"
#include "telear/vision/stereo_calibration.hpp"

namespace telear::vision {

struct CalibrationReport {
  CalibrationPattern pattern;
  cv::Size image_size;
  std::size_t views_given = 0;
  std::vector<RejectedView> skipped;  // left out before calibrating (detection, decoding)
  int reordered_pairs = 0;            // stereo chessboards whose right corners were reversed
  // Exactly one of these is set.
  std::optional<MonoCalibration> mono;
  std::optional<StereoCalibration> stereo;
};

// The report as pretty-printed JSON text (2-space indent).
std::string calibration_report_json(const CalibrationReport& report);

// A human-readable summary: parameters with standard deviations, stereo geometry, a per-view
// table and the views left out with their reasons.
std::string calibration_summary(const CalibrationReport& report);

// The result as ROS camera_info files, (path, YAML text) pairs: PREFIX.yaml for a mono
// calibration, PREFIX_left.yaml and PREFIX_right.yaml for a stereo one; none for "".
std::vector<std::pair<std::string, std::string>> ros_camera_info_files(
    const std::string& prefix, const CalibrationReport& report);

}  // namespace telear::vision
