#pragma once
// Loading robot models from files: a standard-DH YAML table (telear's own small format,
// docs/robot-files.md) or a URDF (urdfdom). Untrusted input: every failure is a Result
// error naming the file and what is wrong with it.

#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// `name_or_path` is a robot shipped in data/robots (e.g. "puma560"), or a path to a
// .yaml/.yml DH table, a robot file (.yaml with `urdf:`) or a .urdf file: the chain of
// load_robot_description (core/robot_description.hpp), without reading companion files.
Result<RobotModelPtr> load_robot(const std::string& name_or_path);
// The same with a tip link (spec.tip) for URDF robots.
Result<RobotModelPtr> load_robot(const RobotSpec& spec);

Result<RobotModel> load_dh_yaml_file(const std::string& path);
Result<RobotModel> parse_dh_yaml(const std::string& text, const std::string& source);

// Loads the chain from the URDF's root link to `tip_link` (empty: the single leaf link;
// an error listing the leaves when the tree branches). Fixed joints are folded into their
// neighbours; docs/robot-files.md lists what is refused.
Result<RobotModel> load_urdf_file(const std::string& path, const std::string& tip_link = "");
Result<RobotModel> parse_urdf(const std::string& text, const std::string& source,
                              const std::string& tip_link = "");

// The directory holding robots/, rigs/, cameras/, in this order (docs/install.md):
//   1. $TELEAR_DATA_DIR when set and not empty (not checked: a wrong one fails on use);
//   2. <directory of the running program>/../share/telear/data when that directory exists
//      (an installed telear: PREFIX/bin/telear reads PREFIX/share/telear/data);
//   3. the source tree's data/ directory recorded at build time (programs in the build tree).
std::string data_directory();

}  // namespace telear::core
