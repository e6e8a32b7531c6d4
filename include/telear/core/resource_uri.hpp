#pragma once
// Where a robot's resource lies (its URDF from a robot file, a URDF's mesh files): resolving
// ROS resource URIs to paths, without needing ROS.
//
// Accepted forms:
//   package://PKG/REL   REL inside the package directory of PKG (search below)
//   file:///ABS         the absolute path /ABS
//   /ABS                an absolute path
//   REL                 a path relative to the URDF's directory (base_dir)
//
// package:// search (as ROS finds packages, without needing ROS): the directories are tried in
// this order: the caller's --package-path directories, then the robot file's package_paths,
// then the entries of ROS_PACKAGE_PATH. In each directory D the package PKG is
//   1. D/PKG, if it is a directory;
//   2. D itself, if D's name is PKG;
//   3. a sub-directory of D at depth 1..3 named PKG that holds a package.xml (entries visited
//      in name order, breadth first).
// The first package directory holding REL wins. Errors list every place looked, e.g.
//   mesh 'package://arm/meshes/forearm.stl' not found (looked in /a/arm, /b/arm; set
//   ROS_PACKAGE_PATH or pass --package-path DIR)
// (the geometry layer prefixes the link: "link 'forearm': mesh ...").

#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::core {

struct ResourceSearchPaths {
  std::vector<std::string> package_paths;        // the caller's --package-path, in order
  std::vector<std::string> robot_package_paths;  // the robot file's package_paths
  std::vector<std::string> ros_package_path;     // ROS_PACKAGE_PATH's entries
  std::string base_dir;                          // relative paths: the URDF's directory
};

// A ':'-separated list (ROS_PACKAGE_PATH) split into its non-empty entries.
std::vector<std::string> split_package_path(const std::string& value);

// ROS_PACKAGE_PATH of this process, split; empty when unset.
std::vector<std::string> ros_package_path_from_environment();

// The package's directories in search order (every match, first is ROS's choice).
std::vector<std::string> find_package_dirs(const std::string& package,
                                           const ResourceSearchPaths& search);

// The absolute path of an existing file for `uri`, or an error naming the URI, why and, for
// package://, every place looked.
// `what` names the resource in messages ("mesh", "urdf").
Result<std::string> resolve_resource_uri(const std::string& uri, const ResourceSearchPaths& search,
                                         const std::string& what = "mesh");

}  // namespace telear::core
