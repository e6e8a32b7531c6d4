#include "apps/eval_command.hpp"

#include <ostream>
#include <string>
#include <vector>

#include "apps/command_failure.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/vision/accuracy_check.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "telear/vision/registered_camera_file.hpp"

namespace telear::cli {
int run_eval(const EvalOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear eval"};
  if (options.truth.empty()) return fail("--truth: give the true cameras (truth.yaml)");
  if (options.estimate.empty())
    return fail("--estimate: give the registered camera file (telear register -o)");
  if (options.configurations < 0 || options.configurations > 10000)
    return fail("--configurations " + std::to_string(options.configurations) +
                " is outside 0..10000");
  if (!(options.spacing_m >= 0.001 && options.spacing_m <= 1.0))
    return fail("--spacing must be within 0.001..1 m");
  if (!options.json.empty()) {
    if (Status s = vision::check_output_path(options.json, "--json"); !s)
      return fail(s.error().message);
  }
  auto truth = vision::load_registered_pair(options.truth, "--truth");
  if (!truth) return fail(truth.error().message);
  auto estimate = vision::load_registered_pair(options.estimate, "--estimate");
  if (!estimate) return fail(estimate.error().message);
  auto geometry = options.geometry_options();
  if (!geometry) return fail(geometry.error().message);
  auto robot = geometry::load_robot_assets(options.robot_spec(), *geometry);
  if (!robot) return fail("--robot: " + robot.error().message);
  const core::RobotModelPtr model = robot->model();
  const core::ArmBody body = core::build_arm_body(robot->body);

  vision::AccuracyOptions accuracy_options;
  accuracy_options.configurations = options.configurations;
  accuracy_options.spacing_m = options.spacing_m;
  const vision::AccuracyReport report =
      vision::evaluate_accuracy(*model, body, *truth, *estimate, accuracy_options);

  const std::vector<vision::AccuracyCheck> checks = vision::accuracy_checks(report);
  out << "accuracy of '" << options.estimate << "' against '" << options.truth << "'\n"
      << vision::accuracy_report_text(report, checks);

  if (!options.json.empty()) {
    const std::string json = vision::accuracy_report_json(report, checks);
    if (Status s = vision::write_files_atomically({{options.json, json}}); !s) {
      return fail(s.error().message, 1);
    }
    out << "wrote " << options.json << "\n";
  }
  return 0;
}

}  // namespace telear::cli
