#pragma once
// The simulated robot's *true* geometry: the nominal model with a per-joint offset added to
// every joint's zero, as if each encoder were mounted slightly off. The robot reports the
// nominal model's joint readings q while the real arm sits at the true model's FK(q), i.e. at
// the nominal FK(q + delta):
//
//   true joint i:  before_i * Z(q_i + offset_i + delta_i) * after_i
//
// The renderer draws the "real" scene with the true model at the reported q; registration and
// calibration have a real, known difference to find. Offsets are rad (revolute) or m
// (prismatic), dof() values.

#include <Eigen/Core>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::sim {

// The nominal model with joint_offsets added to the joints' (and the DH table's) offsets.
// Same name, so that per-robot data (e.g. the arm body file) still applies. Fails when the
// offsets are not dof() finite values.
Result<core::RobotModel> with_joint_offsets(const core::RobotModel& nominal,
                                            const Eigen::VectorXd& joint_offsets);

}  // namespace telear::sim
