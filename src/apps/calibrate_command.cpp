#include "apps/calibrate_command.hpp"

#include <ostream>
#include <utility>
#include <vector>

#include "apps/command_failure.hpp"
#include "telear/core/number_format.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/calibration_images.hpp"
#include "telear/vision/calibration_report.hpp"
#include "telear/vision/image_calibration.hpp"

namespace telear::cli {
namespace {

vision::DetectionCallback progress_printer(std::ostream& out) {
  return [&out](const vision::DetectionProgress& p) {
    const int width = static_cast<int>(std::to_string(p.count).size());
    out << core::format_values("[%*zu/%zu] ", width, p.index, p.count) << p.name << ": "
        << p.outcome << std::endl;  // flushed: live progress
  };
}

std::vector<std::string> output_paths(const CalibrateOptions& o) {
  std::vector<std::string> paths = {o.output};
  if (!o.report.empty()) paths.push_back(o.report);
  if (!o.camera_info.empty()) {
    if (o.right.empty()) {
      paths.push_back(o.camera_info + ".yaml");
    } else {
      paths.push_back(o.camera_info + "_left.yaml");
      paths.push_back(o.camera_info + "_right.yaml");
    }
  }
  return paths;
}

}  // namespace

int run_calibrate(const CalibrateOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear calibrate"};
  // Everything that can be checked cheaply, before detection.
  auto pattern = vision::parse_calibration_pattern(options.pattern);
  if (!pattern) return fail("--pattern: " + pattern.error().message);
  auto model = vision::parse_distortion_model(options.model);
  if (!model) return fail("--model: " + model.error().message);
  vision::StereoCalibrationOptions calibration;
  calibration.calibration.model = *model;
  if (*model == vision::DistortionModel::equidistant && options.zero_tangential) {
    return fail(
        "--zero-tangential: the equidistant (fisheye) model has no tangential terms; "
        "leave it out with --model equidistant");
  }
  if (*model != vision::DistortionModel::plumb_bob && options.estimate_k3) {
    return fail(std::string("--estimate-k3: applies to plumb_bob only; --model ") +
                vision::distortion_model_name(*model) + " estimates all its terms");
  }
  calibration.calibration.outlier_factor = options.outlier_factor;
  calibration.calibration.fix_k3 = !options.estimate_k3;
  calibration.calibration.zero_tangential = options.zero_tangential;
  calibration.refine_intrinsics = !options.keep_mono_intrinsics;
  if (Status s = calibration.validate(); !s) {
    return fail("--outlier-factor: " + s.error().message);
  }
  if (options.output.empty()) return fail("-o: give the camera file to write, e.g. -o stereo.yaml");
  const std::vector<std::string> outputs = output_paths(options);
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const char* option =
        i == 0 ? "-o" : (outputs[i] == options.report ? "--report" : "--camera-info");
    if (Status s = vision::check_output_path(outputs[i], option); !s)
      return fail(s.error().message);
    for (std::size_t j = 0; j < i; ++j) {
      if (outputs[i] == outputs[j]) return fail("'" + outputs[i] + "' is given as two outputs");
    }
  }
  auto left = vision::expand_image_glob(options.left, "--left");
  if (!left) return fail(left.error().message);

  std::vector<std::string> right;
  if (!options.right.empty()) {
    auto expanded = vision::expand_image_glob(options.right, "--right");
    if (!expanded) return fail(expanded.error().message);
    right = std::move(*expanded);
  }
  vision::ImageCalibrationProgress progress;
  progress.stage = [&out](const std::string& text) { out << text << std::endl; };
  progress.detection = progress_printer(out);
  auto calibrated = vision::calibrate_image_files(*left, right, *pattern, calibration, progress);
  if (!calibrated) return fail(calibrated.error().message);
  const vision::CalibrationReport& report = *calibrated;

  out << "\n" << vision::calibration_summary(report);

  std::vector<std::pair<std::string, std::string>> files;
  files.emplace_back(options.output, report.stereo
                                         ? vision::stereo_calibration_yaml(*report.stereo, *pattern)
                                         : mono_calibration_yaml(*report.mono, *pattern));
  if (!options.report.empty())
    files.emplace_back(options.report, vision::calibration_report_json(report));
  for (auto& file : vision::ros_camera_info_files(options.camera_info, report))
    files.push_back(std::move(file));
  if (Status s = vision::write_files_atomically(files); !s) return fail(s.error().message, 1);
  out << "\nwrote";
  for (const auto& [path, text] : files) out << " " << path;
  out << "\n";
  return 0;
}

}  // namespace telear::cli
