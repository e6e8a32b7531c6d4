#pragma once
// A camera calibration from image files, mono or stereo, in one call: detection in every
// image or pair (calibration_images.hpp), then the mono or stereo fit (mono_calibration.hpp,
// stereo_calibration.hpp), and the report of what was used and what was left out
// (calibration_report.hpp). `telear calibrate` and the demo's calibration pipeline both run
// it, so a set of images calibrates the same way from either.

#include <functional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/vision/calibration_images.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/calibration_report.hpp"
#include "telear/vision/stereo_calibration.hpp"

namespace telear::vision {

struct ImageCalibrationProgress {
  // Before each stage: "detecting chessboard:9x6:0.025 in 13 image pairs", "calibrating the
  // stereo pair from 12 pairs" (mono: "... in 13 images", "calibrating the camera from ...").
  std::function<void(const std::string&)> stage;
  DetectionCallback detection;  // after each image or pair
};

// Mono when `right` is empty, else stereo pairs matched by index (`options.calibration` holds
// the mono fit's options). Errors: detection's, or the fit's followed by "; 2 of 13 pairs were
// skipped (see the lines above)" when views were left out before it.
Result<CalibrationReport> calibrate_image_files(const std::vector<std::string>& left,
                                                const std::vector<std::string>& right,
                                                const CalibrationPattern& pattern,
                                                const StereoCalibrationOptions& options,
                                                const ImageCalibrationProgress& progress = {});

}  // namespace telear::vision
