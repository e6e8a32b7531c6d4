#pragma once
// The "real" robot a simulated rig shows: the rig file's robot (a shipped name or a file,
// docs/simulation.md), drawn with the rig's body file when it names one (the PUMA's rig draws
// the real arm with another body than the operator's ghost), else the robot's own body: its
// URDF meshes or its DH body file. Every program that renders the simulated scene loads the
// robot through here, so a rig of any arm works the same in capture, observations, frames
// and the vision server's source.

#include <Eigen/Core>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/sim/stereo_rig.hpp"

namespace telear::sim {

// `robot` overrides the rig's robot when its name_or_path is not empty (e.g. --robot). The
// meshes are loaded as they are (options.visual_tolerance_m is ignored: no level of detail).
Result<geometry::RobotAssets> load_rig_robot(const StereoRig& rig,
                                             const core::RobotSpec& robot = {},
                                             const geometry::GeometryOptions& options = {});

// Where a simulated arm rests when nothing says otherwise: the first of the named
// configurations qr (the PUMA's ready pose), ready, home; else all joints at 0.
Eigen::VectorXd rest_configuration(const core::RobotModel& model);

}  // namespace telear::sim
