#pragma once
// The robot options every command that takes --robot shares (docs/cli.md):
//   --robot NAME|FILE       a shipped name (data/robots/NAME.yaml), a robot file, a DH table or
//                           a URDF
//   --tip LINK              the tip link when the URDF tree has several leaves
//   --package-path DIR      searched first for package:// URIs (repeatable), then the robot
//                           file's package_paths, then $ROS_PACKAGE_PATH
//   --missing-meshes error|primitives
//                           a mesh that cannot be found fails (default) or is drawn as a
//                           stand-in with a warning
// Options structs derive from RobotArguments so that `options.robot` stays the robot's name.

#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/robot_geometry.hpp"

namespace telear::cli {

struct RobotArguments {
  std::string robot = "puma560";
  std::string tip;
  std::vector<std::string> package_paths;
  std::string missing_meshes = "error";

  core::RobotSpec robot_spec() const { return {robot, tip, package_paths}; }
  // The mesh search and stand-in policy; an unknown --missing-meshes value is an error.
  Result<geometry::GeometryOptions> geometry_options() const;
};

}  // namespace telear::cli
