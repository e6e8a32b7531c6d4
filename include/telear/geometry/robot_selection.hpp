#pragma once
// Which robot a command works on and how its meshes are found: what --robot, --tip,
// --package-path and --missing-meshes say (docs/cli.md), shared by every command that takes
// a robot and by `telear bench kin`. No command-line parser here: the options are registered
// where the command line is built (apps/cli_conventions.cpp), into these fields.
//   robot            a shipped name (data/robots/NAME.yaml), a robot file, a DH table or a URDF
//   tip              the tip link when the URDF tree has several leaves
//   package_paths    searched first for package:// URIs, then the robot file's package_paths,
//                    then $ROS_PACKAGE_PATH
//   missing_meshes   "error" (a mesh that cannot be found fails) or "primitives" (drawn as a
//                    stand-in with a warning)
// Options structs derive from RobotSelection so that `options.robot` stays the robot's name.

#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/robot_geometry.hpp"

namespace telear::geometry {

struct RobotSelection {
  std::string robot = "puma560";
  std::string tip;
  std::vector<std::string> package_paths;
  std::string missing_meshes = "error";

  core::RobotSpec robot_spec() const { return {robot, tip, package_paths}; }
  // The mesh search and stand-in policy. Error: "missing_meshes: 'x' is not error or
  // primitives".
  Result<GeometryOptions> geometry_options() const;
};

}  // namespace telear::geometry
