#pragma once
// A registration target (telear/vision/registration_target.hpp: an ArUco marker, an AprilTag,
// a ChArUco board) as geometry on the simulated flange, where the robot's marker mount
// (telear/core/marker_mount.hpp) places it. Like the calibration targets
// (calibration_targets.hpp) the print is geometry: the dark cells and squares are exact quads
// at z = 0 of the target frame (facing +z, towards the viewer), in front of a white plate of
// the printed size 0.2 mm behind them and a dark backing plate behind that, so their edges
// and corners are where the target's points say, to float precision.

#include <Eigen/Geometry>
#include <vector>

#include "telear/core/mesh.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::sim {

struct FlangeTarget {
  vision::RegistrationTarget target;
  Eigen::Isometry3d T_flange_target = Eigen::Isometry3d::Identity();
  core::Mesh mesh;                             // flange frame
  std::vector<Eigen::Vector3d> points_flange;  // the target's points, by id
};

FlangeTarget make_flange_target(const vision::RegistrationTarget& target,
                                const Eigen::Isometry3d& T_flange_target);

}  // namespace telear::sim
