#include "apps/eval_command.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/vision/accuracy_check.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "telear/vision/registered_camera_file.hpp"

namespace telear::cli {
namespace {

constexpr const char* kCommand = "telear eval: ";

int fail(std::ostream& err, const std::string& message, int code = 2) {
  err << kCommand << message << "\n";
  return code;
}

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
  auto truth = vision::load_registered_pair(options.truth, "--truth");
  if (!truth) return fail(err, truth.error().message);
  auto estimate = vision::load_registered_pair(options.estimate, "--estimate");
  if (!estimate) return fail(err, estimate.error().message);
  auto geometry = options.geometry_options();
  if (!geometry) return fail(err, geometry.error().message);
  auto robot = geometry::load_robot_assets(options.robot_spec(), *geometry);
  if (!robot) return fail(err, "--robot: " + robot.error().message);
  const core::RobotModelPtr model = robot->model();
  const core::ArmBody body = core::build_arm_body(robot->body);

  vision::AccuracyOptions accuracy_options;
  accuracy_options.configurations = options.configurations;
  accuracy_options.spacing_m = options.spacing_m;
  const vision::AccuracyReport report =
      vision::evaluate_accuracy(*model, body, *truth, *estimate, accuracy_options);

  out << "accuracy of '" << options.estimate << "' against '" << options.truth << "'\n";
  for (const auto* eye : {&report.left, &report.right}) {
    const vision::CameraModel& t = eye->truth;
    const vision::CameraModel& e = eye->estimate;
    out << "\n"
        << (eye == &report.left ? "left" : "right")
        << " camera            truth       estimate      error\n";
    out << format("  fx             %12.4f  %12.4f  %+9.4f %%\n", t.fx, e.fx,
                  100.0 * (e.fx - t.fx) / t.fx);
    out << format("  fy             %12.4f  %12.4f  %+9.4f %%\n", t.fy, e.fy,
                  100.0 * (e.fy - t.fy) / t.fy);
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
  }
  out << format("\nbaseline         truth %.4f mm  estimate %.4f mm  error %+.4f mm\n",
                1000.0 * report.baseline_truth_m, 1000.0 * report.baseline_estimate_m,
                1000.0 * (report.baseline_estimate_m - report.baseline_truth_m));
  out << "overlay: " << report.configurations << " arm configurations x "
      << report.samples_per_configuration << " body points\n";

  const std::vector<vision::AccuracyCheck> checks = vision::accuracy_checks(report);
  out << "\ntargets (issue 4 item 7)\n";
  for (const vision::AccuracyCheck& c : checks) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-24s %10.4f  <= %-7g %s\n", c.name.c_str(), c.value,
                  c.limit, c.pass() ? "PASS" : "FAIL");
    out << line;
  }
  out << "overall: " << (vision::all_pass(checks) ? "PASS" : "FAIL") << "\n";

  if (!options.json.empty()) {
    const std::string json = vision::accuracy_report_json(report, checks);
    if (Status s = vision::write_files_atomically({{options.json, json}}); !s) {
      return fail(err, s.error().message, 1);
    }
    out << "wrote " << options.json << "\n";
  }
  return 0;
}

}  // namespace telear::cli
