#include "telear/vision/image_calibration.hpp"

#include <utility>

namespace telear::vision {
namespace {

// "; 11 of 13 pairs were skipped (see the lines above)" when views were lost on the way.
std::string skipped_note(std::size_t skipped, std::size_t given, const char* what) {
  if (skipped == 0) return "";
  return "; " + std::to_string(skipped) + " of " + std::to_string(given) + " " + what +
         " were skipped (see the lines above)";
}

}  // namespace

Result<CalibrationReport> calibrate_image_files(const std::vector<std::string>& left,
                                                const std::vector<std::string>& right,
                                                const CalibrationPattern& pattern,
                                                const StereoCalibrationOptions& options,
                                                const ImageCalibrationProgress& progress) {
  const auto stage = [&progress](const std::string& text) {
    if (progress.stage) progress.stage(text);
  };
  CalibrationReport report;
  report.pattern = pattern;
  report.views_given = left.size();
  if (!right.empty()) {
    stage("detecting " + pattern.spec() + " in " + std::to_string(left.size()) + " image pairs");
    auto views = detect_in_image_pairs(left, right, pattern, progress.detection);
    if (!views) return views.error();
    report.image_size = views->image_size;
    report.skipped = views->rejected;
    report.reordered_pairs = views->reordered_pairs;
    stage("calibrating the stereo pair from " + std::to_string(views->views.size()) + " pairs");
    auto result = calibrate_stereo(pattern, views->views, views->image_size, options);
    if (!result) {
      return Error{result.error().message +
                   skipped_note(views->rejected.size(), left.size(), "pairs")};
    }
    report.stereo = std::move(*result);
    return report;
  }
  stage("detecting " + pattern.spec() + " in " + std::to_string(left.size()) + " images");
  auto views = detect_in_images(left, pattern, progress.detection);
  if (!views) return views.error();
  report.image_size = views->image_size;
  report.skipped = views->rejected;
  stage("calibrating the camera from " + std::to_string(views->views.size()) + " images");
  auto result = calibrate_mono(pattern, views->views, views->image_size, options.calibration);
  if (!result) {
    return Error{result.error().message +
                 skipped_note(views->rejected.size(), left.size(), "images")};
  }
  report.mono = std::move(*result);
  return report;
}

}  // namespace telear::vision
