#pragma once
// Where the demo's registration capture starts (the operator's jog before capturing,
// simulated): an observation of the calibration pipeline (sim/marker_observations.hpp) where
// both cameras saw the marker and from which the straight move to the task's ready pose, which
// ends the capture, is free of contact as the robot server checks it (the arm itself and the
// workspace's static objects). The first such observation.
//
// Why the move and not only the marker (issue 26): the observations are random in-limit
// configurations, and on a UR-type arm (+-360 deg joints) the first one with the marker in view
// had the base inside the upper arm, where the server refused every move of the capture.

#include <Eigen/Core>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/workspace.hpp"
#include "telear/vision/observations_file.hpp"

namespace telear::lab {

// Errors: no observation shows the marker to both cameras; none of those has a free move to
// ready_q (both say how many were looked at); the collision checker's.
Result<Eigen::VectorXd> capture_start_pose(const vision::RegistrationObservations& observations,
                                           const core::RobotDescription& description,
                                           const core::Workspace& workspace,
                                           const Eigen::VectorXd& ready_q);

}  // namespace telear::lab
