#include "telear/vision/accuracy_check.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

namespace telear::vision {

bool AccuracyCheck::pass() const {
  return std::isfinite(value) && value <= limit;
}

bool all_pass(const std::vector<AccuracyCheck>& checks) {
  for (const AccuracyCheck& c : checks) {
    if (!c.pass()) return false;
  }
  return true;
}

std::vector<AccuracyCheck> accuracy_checks(const AccuracyReport& report,
                                           const AccuracyTargets& targets) {
  std::vector<AccuracyCheck> checks;
  for (const EyeAccuracy* eye : {&report.left, &report.right}) {
    const std::string p = eye == &report.left ? "left " : "right ";
    const CameraModel& t = eye->truth;
    const CameraModel& e = eye->estimate;
    checks.push_back(
        {p + "fx error %", std::abs(100.0 * (e.fx - t.fx) / t.fx), targets.focal_percent});
    checks.push_back(
        {p + "fy error %", std::abs(100.0 * (e.fy - t.fy) / t.fy), targets.focal_percent});
    checks.push_back({p + "cx error px", std::abs(e.cx - t.cx), targets.principal_point_px});
    checks.push_back({p + "cy error px", std::abs(e.cy - t.cy), targets.principal_point_px});
    checks.push_back(
        {p + "registration mm", eye->registration.position_mm, targets.registration_mm});
    checks.push_back(
        {p + "registration deg", eye->registration.rotation_deg, targets.registration_deg});
    checks.push_back({p + "overlay RMS px", eye->overlay.rms_px, targets.overlay_rms_px});
    checks.push_back({p + "overlay max px", eye->overlay.max_px, targets.overlay_max_px});
  }
  const double baseline_error_mm = 1000.0 * (report.baseline_estimate_m - report.baseline_truth_m);
  checks.push_back({"baseline error mm", std::abs(baseline_error_mm), targets.baseline_mm});
  return checks;
}

std::string accuracy_report_json(const AccuracyReport& report,
                                 const std::vector<AccuracyCheck>& checks) {
  nlohmann::json json;
  for (const EyeAccuracy* eye : {&report.left, &report.right}) {
    const CameraModel& t = eye->truth;
    const CameraModel& e = eye->estimate;
    json[eye == &report.left ? "left" : "right"] = {
        {"truth",
         {{"fx", t.fx}, {"fy", t.fy}, {"cx", t.cx}, {"cy", t.cy}, {"kc", t.kc.as_array()}}},
        {"estimate",
         {{"fx", e.fx}, {"fy", e.fy}, {"cx", e.cx}, {"cy", e.cy}, {"kc", e.kc.as_array()}}},
        {"fx_error_percent", 100.0 * (e.fx - t.fx) / t.fx},
        {"fy_error_percent", 100.0 * (e.fy - t.fy) / t.fy},
        {"cx_error_px", e.cx - t.cx},
        {"cy_error_px", e.cy - t.cy},
        {"registration_mm", eye->registration.position_mm},
        {"registration_deg", eye->registration.rotation_deg},
        {"overlay_rms_px", eye->overlay.rms_px},
        {"overlay_max_px", eye->overlay.max_px},
        {"overlay_points", eye->overlay.points}};
  }
  json["baseline_truth_mm"] = 1000.0 * report.baseline_truth_m;
  json["baseline_estimate_mm"] = 1000.0 * report.baseline_estimate_m;
  json["overlay_configurations"] = report.configurations;
  json["overlay_samples_per_configuration"] = report.samples_per_configuration;
  nlohmann::json json_checks = nlohmann::json::array();
  for (const AccuracyCheck& c : checks) {
    json_checks.push_back(
        {{"name", c.name}, {"value", c.value}, {"limit", c.limit}, {"pass", c.pass()}});
  }
  json["checks"] = json_checks;
  json["pass"] = all_pass(checks);
  return json.dump(2) + "\n";
}

}  // namespace telear::vision
