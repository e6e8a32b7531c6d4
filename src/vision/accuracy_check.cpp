#include "telear/vision/accuracy_check.hpp"

#include <array>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "telear/core/number_format.hpp"

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
         {{"fx", t.fx},
          {"fy", t.fy},
          {"cx", t.cx},
          {"cy", t.cy},
          {"distortion_model", distortion_model_name(t.kc.model)},
          {"kc", t.kc.coefficients()}}},
        {"estimate",
         {{"fx", e.fx},
          {"fy", e.fy},
          {"cx", e.cx},
          {"cy", e.cy},
          {"distortion_model", distortion_model_name(e.kc.model)},
          {"kc", e.kc.coefficients()}}},
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

std::string accuracy_report_text(const AccuracyReport& report,
                                 const std::vector<AccuracyCheck>& checks) {
  using core::format_number;
  std::ostringstream out;
  // "  fx             1000.0000     1000.1234    +0.0123 %"
  const auto row = [&out](const std::string& label, double truth, double estimate, double error,
                          const char* value_format, const char* error_format,
                          const std::string& unit) {
    out << "  " << std::left << std::setw(15) << label << format_number(truth, value_format) << "  "
        << format_number(estimate, value_format) << "  " << format_number(error, error_format)
        << unit << "\n";
  };
  for (const auto* eye : {&report.left, &report.right}) {
    const CameraModel& t = eye->truth;
    const CameraModel& e = eye->estimate;
    out << "\n"
        << (eye == &report.left ? "left" : "right")
        << " camera            truth       estimate      error\n";
    row("fx", t.fx, e.fx, 100.0 * (e.fx - t.fx) / t.fx, "%12.4f", "%+9.4f", " %");
    row("fy", t.fy, e.fy, 100.0 * (e.fy - t.fy) / t.fy, "%12.4f", "%+9.4f", " %");
    row("cx", t.cx, e.cx, e.cx - t.cx, "%12.4f", "%+9.4f", " px");
    row("cy", t.cy, e.cy, e.cy - t.cy, "%12.4f", "%+9.4f", " px");
    const std::vector<double> kt = t.kc.coefficients();
    const std::vector<double> ke = e.kc.coefficients();
    const std::vector<const char*> names = t.kc.coefficient_names();
    for (std::size_t i = 0; i < std::min(kt.size(), ke.size()); ++i)
      row(names[i], kt[i], ke[i], ke[i] - kt[i], "%12.6f", "%+9.6f", "");
    out << "  registration   " << format_number(eye->registration.position_mm, "%9.4f") << " mm  "
        << format_number(eye->registration.rotation_deg, "%9.5f") << " deg\n";
    out << "  overlay        RMS " << format_number(eye->overlay.rms_px, "%.4f") << " px  max "
        << format_number(eye->overlay.max_px, "%.4f") << " px  ("
        << format_number(static_cast<double>(eye->overlay.points), "%.0f")
        << " point projections)\n";
  }
  out << "\nbaseline         truth " << format_number(1000.0 * report.baseline_truth_m, "%.4f")
      << " mm  estimate " << format_number(1000.0 * report.baseline_estimate_m, "%.4f")
      << " mm  error "
      << format_number(1000.0 * (report.baseline_estimate_m - report.baseline_truth_m), "%+.4f")
      << " mm\n";
  out << "overlay: " << report.configurations << " arm configurations x "
      << report.samples_per_configuration << " body points\n";
  out << "\ntargets (issue 4 item 7)\n";
  for (const AccuracyCheck& c : checks) {
    out << "  " << std::left << std::setw(24) << c.name << " " << format_number(c.value, "%10.4f")
        << "  <= " << format_number(c.limit, "%-7g") << " " << (c.pass() ? "PASS" : "FAIL") << "\n";
  }
  out << "overall: " << (all_pass(checks) ? "PASS" : "FAIL") << "\n";
  return out.str();
}

}  // namespace telear::vision
