#include "apps/eval_command.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/overlay_accuracy.hpp"

namespace telear::cli {
namespace {

constexpr const char* kCommand = "telear eval: ";

int fail(std::ostream& err, const std::string& message, int code = 2) {
  err << kCommand << message << "\n";
  return code;
}

// A stereo camera file with both poses, or an error naming the option.
Result<vision::StereoCameraModel> load_registered_pair(const std::string& path,
                                                       const char* option) {
  auto file = vision::load_camera_file(path);
  if (!file) return Error{std::string(option) + ": " + file.error().message};
  if (!file->is_stereo()) {
    return Error{std::string(option) + " '" + path + "' is a mono camera file; give a stereo one"};
  }
  if (!file->left_has_pose || !file->right_has_pose) {
    return Error{std::string(option) + " '" + path +
                 "' has no T_cam_base for both eyes (register it first: telear register)"};
  }
  return vision::StereoCameraModel{file->left, *file->right};
}

struct Check {
  std::string name;
  double value;
  double limit;
  bool pass() const { return std::isfinite(value) && value <= limit; }
};

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char line[200];
  std::snprintf(line, sizeof line, fmt, a, b, c, d);
  return line;
}

}  // namespace

int run_eval(const EvalOptions& options, std::ostream& out, std::ostream& err) {
  if (options.truth.empty()) return fail(err, "--truth: give the true cameras (truth.yaml)");
  if (options.estimate.empty())
    return fail(err, "--estimate: give the registered camera file (telear register -o)");
  if (options.configurations < 0 || options.configurations > 10000)
    return fail(
        err, "--configurations " + std::to_string(options.configurations) + " is outside 0..10000");
  if (!(options.spacing_m >= 0.001 && options.spacing_m <= 1.0))
    return fail(err, "--spacing must be within 0.001..1 m");
  if (!options.json.empty()) {
    if (Status s = vision::check_output_path(options.json, "--json"); !s)
      return fail(err, s.error().message);
  }
  auto truth = load_registered_pair(options.truth, "--truth");
  if (!truth) return fail(err, truth.error().message);
  auto estimate = load_registered_pair(options.estimate, "--estimate");
  if (!estimate) return fail(err, estimate.error().message);
  auto model = core::load_robot(options.robot);
  if (!model) return fail(err, "--robot: " + model.error().message);
  auto description = core::body_description_for(**model);
  if (!description) return fail(err, "--robot: " + description.error().message);
  const core::ArmBody body = core::build_arm_body(*description);

  vision::AccuracyOptions accuracy_options;
  accuracy_options.configurations = options.configurations;
  accuracy_options.spacing_m = options.spacing_m;
  const vision::AccuracyReport report =
      vision::evaluate_accuracy(**model, body, *truth, *estimate, accuracy_options);

  const AccuracyTargets targets;
  std::vector<Check> checks;
  nlohmann::json json;
  out << "accuracy of '" << options.estimate << "' against '" << options.truth << "'\n";
  for (const auto* eye : {&report.left, &report.right}) {
    const bool left = eye == &report.left;
    const char* name = left ? "left" : "right";
    const vision::CameraModel& t = eye->truth;
    const vision::CameraModel& e = eye->estimate;
    const double fx_pct = 100.0 * (e.fx - t.fx) / t.fx;
    const double fy_pct = 100.0 * (e.fy - t.fy) / t.fy;
    out << "\n" << name << " camera            truth       estimate      error\n";
    out << format("  fx             %12.4f  %12.4f  %+9.4f %%\n", t.fx, e.fx, fx_pct);
    out << format("  fy             %12.4f  %12.4f  %+9.4f %%\n", t.fy, e.fy, fy_pct);
    out << format("  cx             %12.4f  %12.4f  %+9.4f px\n", t.cx, e.cx, e.cx - t.cx);
    out << format("  cy             %12.4f  %12.4f  %+9.4f px\n", t.cy, e.cy, e.cy - t.cy);
    const std::array<double, 5> kt = t.kc.as_array();
    const std::array<double, 5> ke = e.kc.as_array();
    const char* names[5] = {"k1", "k2", "p1", "p2", "k3"};
    for (int i : {0, 1, 4, 2, 3}) {
      out << "  " << names[i]
          << format("             %12.6f  %12.6f  %+9.6f\n", kt[i], ke[i], ke[i] - kt[i]);
    }
    out << format("  registration   %9.4f mm  %9.5f deg\n", eye->registration.position_mm,
                  eye->registration.rotation_deg);
    out << format("  overlay        RMS %.4f px  max %.4f px  (%.0f point projections)\n",
                  eye->overlay.rms_px, eye->overlay.max_px,
                  static_cast<double>(eye->overlay.points));
    const std::string p = std::string(name) + " ";
    checks.push_back({p + "fx error %", std::abs(fx_pct), targets.focal_percent});
    checks.push_back({p + "fy error %", std::abs(fy_pct), targets.focal_percent});
    checks.push_back({p + "cx error px", std::abs(e.cx - t.cx), targets.principal_point_px});
    checks.push_back({p + "cy error px", std::abs(e.cy - t.cy), targets.principal_point_px});
    checks.push_back(
        {p + "registration mm", eye->registration.position_mm, targets.registration_mm});
    checks.push_back(
        {p + "registration deg", eye->registration.rotation_deg, targets.registration_deg});
    checks.push_back({p + "overlay RMS px", eye->overlay.rms_px, targets.overlay_rms_px});
    checks.push_back({p + "overlay max px", eye->overlay.max_px, targets.overlay_max_px});
    json[name] = {
        {"truth", {{"fx", t.fx}, {"fy", t.fy}, {"cx", t.cx}, {"cy", t.cy}, {"kc", kt}}},
        {"estimate", {{"fx", e.fx}, {"fy", e.fy}, {"cx", e.cx}, {"cy", e.cy}, {"kc", ke}}},
        {"fx_error_percent", fx_pct},
        {"fy_error_percent", fy_pct},
        {"cx_error_px", e.cx - t.cx},
        {"cy_error_px", e.cy - t.cy},
        {"registration_mm", eye->registration.position_mm},
        {"registration_deg", eye->registration.rotation_deg},
        {"overlay_rms_px", eye->overlay.rms_px},
        {"overlay_max_px", eye->overlay.max_px},
        {"overlay_points", eye->overlay.points}};
  }
  const double baseline_error_mm = 1000.0 * (report.baseline_estimate_m - report.baseline_truth_m);
  out << format("\nbaseline         truth %.4f mm  estimate %.4f mm  error %+.4f mm\n",
                1000.0 * report.baseline_truth_m, 1000.0 * report.baseline_estimate_m,
                baseline_error_mm);
  out << "overlay: " << report.configurations << " arm configurations x "
      << report.samples_per_configuration << " body points\n";
  checks.push_back({"baseline error mm", std::abs(baseline_error_mm), targets.baseline_mm});

  out << "\ntargets (issue 4 item 7)\n";
  bool all = true;
  nlohmann::json json_checks = nlohmann::json::array();
  for (const Check& c : checks) {
    all = all && c.pass();
    char line[160];
    std::snprintf(line, sizeof line, "  %-24s %10.4f  <= %-7g %s\n", c.name.c_str(), c.value,
                  c.limit, c.pass() ? "PASS" : "FAIL");
    out << line;
    json_checks.push_back(
        {{"name", c.name}, {"value", c.value}, {"limit", c.limit}, {"pass", c.pass()}});
  }
  out << "overall: " << (all ? "PASS" : "FAIL") << "\n";

  if (!options.json.empty()) {
    json["baseline_truth_mm"] = 1000.0 * report.baseline_truth_m;
    json["baseline_estimate_mm"] = 1000.0 * report.baseline_estimate_m;
    json["overlay_configurations"] = report.configurations;
    json["overlay_samples_per_configuration"] = report.samples_per_configuration;
    json["checks"] = json_checks;
    json["pass"] = all;
    if (Status s = vision::write_files_atomically({{options.json, json.dump(2) + "\n"}}); !s) {
      return fail(err, s.error().message, 1);
    }
    out << "wrote " << options.json << "\n";
  }
  return 0;
}

}  // namespace telear::cli
