#include "apps/calibrate_command.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <utility>
#include <vector>

#include "telear/vision/calibration_file.hpp"
#include "telear/vision/calibration_images.hpp"
#include "telear/vision/calibration_report.hpp"

namespace telear::cli {
namespace {

constexpr const char* kCommand = "telear calibrate: ";

int fail(std::ostream& err, const std::string& message, int code = 2) {
  err << kCommand << message << "\n";
  return code;
}

vision::DetectionCallback progress_printer(std::ostream& out) {
  return [&out](const vision::DetectionProgress& p) {
    const int width = static_cast<int>(std::to_string(p.count).size());
    char counter[32];
    std::snprintf(counter, sizeof counter, "[%*zu/%zu] ", width, p.index, p.count);
    out << counter << p.name << ": " << p.outcome << std::endl;  // flushed: live progress
  };
}

// "; 11 of 13 pairs were skipped (see the lines above)" when views were lost on the way.
std::string skipped_note(std::size_t skipped, std::size_t given, const char* what) {
  if (skipped == 0) return "";
  return "; " + std::to_string(skipped) + " of " + std::to_string(given) + " " + what +
         " were skipped (see the lines above)";
}

// ROS camera_info files of the result: (path, text) pairs.
std::vector<std::pair<std::string, std::string>> camera_info_files(
    const std::string& prefix, const vision::CalibrationReport& r) {
  if (prefix.empty()) return {};
  if (r.mono) return {{prefix + ".yaml", vision::ros_mono_camera_info_yaml(*r.mono, "camera")}};
  return {{prefix + "_left.yaml", vision::ros_stereo_camera_info_yaml(*r.stereo, false, "left")},
          {prefix + "_right.yaml", vision::ros_stereo_camera_info_yaml(*r.stereo, true, "right")}};
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
  // Everything that can be checked cheaply, before detection.
  auto pattern = vision::parse_calibration_pattern(options.pattern);
  if (!pattern) return fail(err, "--pattern: " + pattern.error().message);
  vision::StereoCalibrationOptions calibration;
  calibration.calibration.outlier_factor = options.outlier_factor;
  calibration.calibration.fix_k3 = !options.estimate_k3;
  calibration.calibration.zero_tangential = options.zero_tangential;
  calibration.refine_intrinsics = !options.keep_mono_intrinsics;
  if (Status s = calibration.validate(); !s) {
    return fail(err, "--outlier-factor: " + s.error().message);
  }
  if (options.output.empty())
    return fail(err, "-o: give the camera file to write, e.g. -o stereo.yaml");
  const std::vector<std::string> outputs = output_paths(options);
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const char* option =
        i == 0 ? "-o" : (outputs[i] == options.report ? "--report" : "--camera-info");
    if (Status s = vision::check_output_path(outputs[i], option); !s)
      return fail(err, s.error().message);
    for (std::size_t j = 0; j < i; ++j) {
      if (outputs[i] == outputs[j])
        return fail(err, "'" + outputs[i] + "' is given as two outputs");
    }
  }
  auto left = vision::expand_image_glob(options.left, "--left");
  if (!left) return fail(err, left.error().message);

  vision::CalibrationReport report;
  report.pattern = *pattern;
  const bool stereo = !options.right.empty();
  if (stereo) {
    auto right = vision::expand_image_glob(options.right, "--right");
    if (!right) return fail(err, right.error().message);
    out << "detecting " << pattern->spec() << " in " << left->size() << " image pairs\n";
    auto views = vision::detect_in_image_pairs(*left, *right, *pattern, progress_printer(out));
    if (!views) return fail(err, views.error().message);
    report.image_size = views->image_size;
    report.views_given = left->size();
    report.skipped = views->rejected;
    report.reordered_pairs = views->reordered_pairs;
    out << "calibrating the stereo pair from " << views->views.size() << " pairs" << std::endl;
    auto result = vision::calibrate_stereo(*pattern, views->views, views->image_size, calibration);
    if (!result) {
      return fail(err, result.error().message +
                           skipped_note(views->rejected.size(), left->size(), "pairs"));
    }
    report.stereo = std::move(*result);
  } else {
    out << "detecting " << pattern->spec() << " in " << left->size() << " images\n";
    auto views = vision::detect_in_images(*left, *pattern, progress_printer(out));
    if (!views) return fail(err, views.error().message);
    report.image_size = views->image_size;
    report.views_given = left->size();
    report.skipped = views->rejected;
    out << "calibrating the camera from " << views->views.size() << " images" << std::endl;
    auto result =
        vision::calibrate_mono(*pattern, views->views, views->image_size, calibration.calibration);
    if (!result) {
      return fail(err, result.error().message +
                           skipped_note(views->rejected.size(), left->size(), "images"));
    }
    report.mono = std::move(*result);
  }

  out << "\n" << vision::calibration_summary(report);

  std::vector<std::pair<std::string, std::string>> files;
  files.emplace_back(options.output, report.stereo
                                         ? vision::stereo_calibration_yaml(*report.stereo, *pattern)
                                         : mono_calibration_yaml(*report.mono, *pattern));
  if (!options.report.empty())
    files.emplace_back(options.report, vision::calibration_report_json(report));
  for (auto& file : camera_info_files(options.camera_info, report))
    files.push_back(std::move(file));
  if (Status s = vision::write_files_atomically(files); !s) return fail(err, s.error().message, 1);
  out << "\nwrote";
  for (const auto& [path, text] : files) out << " " << path;
  out << "\n";
  return 0;
}

}  // namespace telear::cli
