#include "telear/sim/rig_robot.hpp"

#include "telear/core/arm_body.hpp"

namespace telear::sim {

Result<geometry::RobotAssets> load_rig_robot(const StereoRig& rig, const core::RobotSpec& robot,
                                             const geometry::GeometryOptions& options) {
  core::RobotSpec spec = robot;
  if (spec.name_or_path.empty()) spec.name_or_path = rig.robot;
  // The simulator is the ground truth: its "real" arm keeps every triangle of the mesh files,
  // whatever level of detail the operator's ghost is drawn at.
  geometry::GeometryOptions truth = options;
  truth.visual_tolerance_m = 0.0;
  auto assets = geometry::load_robot_assets(spec, truth);
  if (!assets) return Error{"rig '" + rig.name + "': robot: " + assets.error().message};
  if (!rig.body_file.empty()) {
    auto body = core::load_body_yaml_file(rig.body_file, *assets->model());
    if (!body) return Error{"rig '" + rig.name + "': " + body.error().message};
    assets->body = std::move(body).value();
  }
  if (rig.marker) assets->description.marker = *rig.marker;
  return assets;
}

Eigen::VectorXd rest_configuration(const core::RobotModel& model) {
  for (const char* name : {"qr", "ready", "home"}) {
    if (auto q = model.named_configuration(name)) return *q;
  }
  return Eigen::VectorXd::Zero(model.dof());
}

}  // namespace telear::sim
