#include "telear/lab/calibration_pipeline.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

#include "telear/core/arm_body.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/sim/calibration_capture.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/accuracy_check.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/calibration_images.hpp"
#include "telear/vision/calibration_report.hpp"
#include "telear/vision/image_calibration.hpp"
#include "telear/vision/observations_file.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "telear/vision/registered_camera_file.hpp"
#include "telear/vision/registration.hpp"

namespace telear::lab {
namespace {

namespace fs = std::filesystem;

Error step_error(const char* step, const std::string& message) {
  return Error{std::string("calibration pipeline: ") + step + ": " + message};
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Step 2: stereo calibration of the captured pairs -> stereo.yaml (+ calibration_report.json),
// with the lens model of the rig's cameras (`telear calibrate --model`): an operator knows
// which kind of lens is mounted, not its coefficients.
Status calibrate(const sim::CalibrationCapture& capture, const std::string& pattern_spec,
                 vision::DistortionModel model, const std::string& output,
                 const std::string& report_file) {
  auto pattern = vision::parse_calibration_pattern(pattern_spec);
  if (!pattern) return pattern.error();
  vision::StereoCalibrationOptions calibration;
  calibration.calibration.model = model;
  auto report = vision::calibrate_image_files(capture.left_images, capture.right_images, *pattern,
                                              calibration);
  if (!report) return report.error();
  return vision::write_files_atomically(
      {{output, vision::stereo_calibration_yaml(*report->stereo, *pattern)},
       {report_file, vision::calibration_report_json(*report)}});
}

// Step 4: the robot base in both cameras -> registered.yaml.
Status register_robot(const core::RobotModel& model, const std::string& stereo_file,
                      const vision::RegistrationObservations& observations,
                      const std::string& output) {
  auto cameras = vision::load_camera_file(stereo_file);
  if (!cameras) return cameras.error();
  if (!cameras->is_stereo()) return Error{"'" + stereo_file + "' is not a stereo camera file"};
  auto T_right_left = vision::stereo_pair_geometry(stereo_file, *cameras);
  if (!T_right_left) return T_right_left.error();
  auto result = vision::register_stereo(model, cameras->left, *cameras->right, *T_right_left,
                                        observations, {});
  if (!result) return result.error();
  vision::StereoCameraModel registered{cameras->left, *cameras->right};
  registered.left.T_cam_base = result->T_left_base;
  registered.right.T_cam_base = result->T_right_base;
  return vision::write_files_atomically(
      {{output, vision::registered_camera_yaml(registered, *T_right_left)}});
}

// Step 5: the estimate against the truth -> eval.json.
Status evaluate(const core::RobotModel& model, const core::BodyDescription& description,
                const std::string& truth_file, const std::string& estimate_file,
                const std::string& output) {
  auto truth = vision::load_registered_pair(truth_file, "truth");
  if (!truth) return truth.error();
  auto estimate = vision::load_registered_pair(estimate_file, "estimate");
  if (!estimate) return estimate.error();
  const core::ArmBody body = core::build_arm_body(description);
  const vision::AccuracyReport report = vision::evaluate_accuracy(model, body, *truth, *estimate);
  return vision::write_files_atomically(
      {{output, vision::accuracy_report_json(report, vision::accuracy_checks(report))}});
}

Result<CalibrationEvaluation> read_evaluation(const std::string& path) {
  CalibrationEvaluation evaluation;
  evaluation.json = read_text(path);
  const nlohmann::json json = nlohmann::json::parse(evaluation.json, nullptr, false);
  if (json.is_discarded() || !json.is_object() || !json.contains("left") ||
      !json.contains("right")) {
    return Error{"'" + path + "' is not an evaluation report (delete the cache folder to redo it)"};
  }
  for (auto [eye, name] : {std::pair{&evaluation.left, "left"}, {&evaluation.right, "right"}}) {
    const nlohmann::json& e = json[name];
    eye->fx_error_percent = e.value("fx_error_percent", 0.0);
    eye->fy_error_percent = e.value("fy_error_percent", 0.0);
    eye->cx_error_px = e.value("cx_error_px", 0.0);
    eye->cy_error_px = e.value("cy_error_px", 0.0);
    eye->registration_mm = e.value("registration_mm", 0.0);
    eye->registration_deg = e.value("registration_deg", 0.0);
    eye->overlay_rms_px = e.value("overlay_rms_px", 0.0);
    eye->overlay_max_px = e.value("overlay_max_px", 0.0);
  }
  evaluation.baseline_truth_mm = json.value("baseline_truth_mm", 0.0);
  evaluation.baseline_estimate_mm = json.value("baseline_estimate_mm", 0.0);
  evaluation.pass = json.value("pass", false);
  return evaluation;
}

}  // namespace

Status CalibrationPipelineOptions::validate() const {
  if (rig_file.empty()) return Error{"rig_file: give the simulated rig's YAML"};
  if (cache_dir.empty()) return Error{"cache_dir: give the folder to keep the results in"};
  if (views < 1 || views > 100) {
    return Error{"views " + std::to_string(views) + " is outside 1..100"};
  }
  if (configurations < 1 || configurations > 500) {
    return Error{"configurations " + std::to_string(configurations) + " is outside 1..500"};
  }
  if (supersample < 1 || supersample > 8) {
    return Error{"supersample " + std::to_string(supersample) + " is outside 1..8"};
  }
  return Status::Ok();
}

Result<CalibrationPipelineResult> run_calibration_pipeline(
    const CalibrationPipelineOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (Status s = options.validate(); !s) return step_error("options", s.error().message);
  std::error_code ec;
  if (!fs::is_regular_file(options.rig_file, ec)) {
    return step_error("capture", "the rig file '" + options.rig_file +
                                     "' does not exist or is not a file; give a rig YAML such "
                                     "as data/rigs/puma560_rig.yaml");
  }
  const fs::path cache(options.cache_dir);
  CalibrationPipelineResult result;
  result.registered_file = (cache / "registered.yaml").string();
  const std::string eval_file = (cache / "eval.json").string();
  const std::string key_file = (cache / "key.txt").string();
  std::ostringstream key;
  // v2: the observations are free of contact (issue 26): a v1 cache may start the capture
  // with the arm in contact with itself, which the robot server refuses.
  key << "telear demo calibration v2\nrig " << options.rig_file << "\nseed " << options.seed
      << "\n";
  // The demo's defaults keep the key of the runs before these options existed.
  if (options.views != 20 || options.configurations != 20 || options.supersample != 4 ||
      options.pattern != "chessboard:9x6:0.03" || options.robot != "puma560") {
    key << "views " << options.views << "\nconfigurations " << options.configurations
        << "\nsupersample " << options.supersample << "\npattern " << options.pattern << "\nrobot "
        << options.robot << "\n";
  }
  if (!options.tip.empty()) key << "tip " << options.tip << "\n";
  result.cached = fs::exists(result.registered_file, ec) && fs::exists(eval_file, ec) &&
                  fs::exists(key_file, ec) && read_text(key_file) == key.str();

  if (!result.cached) {
    fs::create_directories(cache, ec);
    if (ec || !fs::is_directory(cache)) {
      return step_error("cache", "cannot create the folder '" + options.cache_dir +
                                     "': " + (ec ? ec.message() : "not a directory"));
    }
    fs::remove(key_file, ec);
    auto robot = geometry::load_robot_assets(
        {options.robot, options.tip, options.geometry.package_paths}, options.geometry);
    if (!robot) return step_error("register", robot.error().message);
    const core::RobotModelPtr model = robot->model();

    sim::CalibrationCaptureOptions capture_options;
    capture_options.rig_file = options.rig_file;
    capture_options.pattern = options.pattern;
    capture_options.views = options.views;
    capture_options.output_dir = (cache / "capture").string();
    capture_options.seed = options.seed;
    capture_options.supersample = options.supersample;
    auto capture = sim::capture_calibration_views(capture_options);
    if (!capture) return step_error("capture", capture.error().message);

    auto rig = sim::load_stereo_rig(options.rig_file);
    if (!rig) return step_error("calibrate", rig.error().message);
    const std::string stereo_file = (cache / "stereo.yaml").string();
    if (Status s = calibrate(*capture, options.pattern, rig->cameras.left.kc.model, stereo_file,
                             (cache / "calibration_report.json").string());
        !s) {
      return step_error("calibrate", s.error().message);
    }

    sim::MarkerObservationsOptions observe_options;
    observe_options.rig_file = options.rig_file;
    observe_options.robot = options.robot;
    observe_options.tip = options.tip;
    observe_options.geometry = options.geometry;
    observe_options.configurations = options.configurations;
    observe_options.seed = options.seed;
    observe_options.supersample = options.supersample;
    // The demo's capture starts at one of them, on the robot server (lab/capture_start.hpp).
    observe_options.collision_free = true;
    auto observed = sim::simulate_marker_observations(observe_options);
    if (!observed) return step_error("observe", observed.error().message);
    const std::string observations_file = (cache / "observations.yaml").string();
    if (Status s = vision::write_observations_file(observed->observations, observations_file); !s) {
      return step_error("observe", s.error().message);
    }

    if (Status s =
            register_robot(*model, stereo_file, observed->observations, result.registered_file);
        !s) {
      return step_error("register", s.error().message);
    }
    if (Status s =
            evaluate(*model, robot->body, capture->truth_file, result.registered_file, eval_file);
        !s) {
      return step_error("evaluate", s.error().message);
    }
    if (Status s = vision::write_files_atomically({{key_file, key.str()}}); !s) {
      return step_error("cache", s.error().message);
    }
  }

  auto evaluation = read_evaluation(eval_file);
  if (!evaluation) return step_error("evaluate", evaluation.error().message);
  result.evaluation = std::move(*evaluation);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace telear::lab
