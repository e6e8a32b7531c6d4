#pragma once
// Everything a program needs to show and simulate one robot, loaded in one call: the
// description (chain, URDF links, gripper, marker; core/robot_description.hpp) and the visual
// body built from it (robot_geometry.hpp: the URDF's meshes and primitives, or the DH
// robot's body file). The demo, the console, the simulated rig and the commands that draw an
// arm all start here, so `--robot ARM --tip LINK --package-path DIR` means the same
// everywhere.

#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/robot_geometry.hpp"

namespace telear::geometry {

struct RobotAssets {
  core::RobotDescription description;
  core::BodyDescription body;
  std::vector<std::string> warnings;  // stand-ins drawn for missing meshes

  const core::RobotModelPtr& model() const { return description.model; }
  // The registration marker the robot file (or NAME.marker.yaml) mounts; an error naming the
  // robot when it has none.
  Result<core::MarkerMount> marker() const;
};

Result<RobotAssets> load_robot_assets(const core::RobotSpec& spec,
                                      const GeometryOptions& options = {});

}  // namespace telear::geometry
