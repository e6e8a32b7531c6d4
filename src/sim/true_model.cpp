#include "telear/sim/true_model.hpp"

#include <cmath>
#include <string>

namespace telear::sim {

Result<core::RobotModel> with_joint_offsets(const core::RobotModel& nominal,
                                            const Eigen::VectorXd& joint_offsets) {
  if (joint_offsets.size() != nominal.dof()) {
    return Error{"true joint offsets: expected " + std::to_string(nominal.dof()) +
                 " values for robot '" + nominal.name() + "', got " +
                 std::to_string(joint_offsets.size())};
  }
  for (int j = 0; j < nominal.dof(); ++j) {
    if (!std::isfinite(joint_offsets[j])) {
      return Error{"true joint offsets: the value for joint " + std::to_string(j + 1) + " (" +
                   nominal.joint(j).name + ") is not a finite number"};
    }
  }
  core::RobotModel::Description d;
  d.name = nominal.name();
  d.joints = nominal.joints();
  d.T_flange_tool = nominal.T_flange_tool();
  d.named_configurations = nominal.named_configurations();
  d.dh = nominal.dh();
  d.source = nominal.source() + " (simulated true geometry: joint offsets added)";
  for (int j = 0; j < nominal.dof(); ++j) {
    d.joints[static_cast<size_t>(j)].offset += joint_offsets[j];
    if (d.dh) (*d.dh)[static_cast<size_t>(j)].offset += joint_offsets[j];
  }
  return core::RobotModel::create(std::move(d));
}

}  // namespace telear::sim
