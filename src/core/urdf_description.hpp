#pragma once
// Internal to core: a URDF turned into telear's description before the robot file adds its
// facts (name, named configurations). The chain model is left as a RobotModel::Description so
// that the caller can still name it and add configurations before RobotModel::create.
//
// Chain frames (robot_model.hpp): frame 0 is the root link, frame i the LAST link reached from
// the child of movable chain joint i through fixed chain joints (the parent of joint i+1, or
// the tip), because fixed chain joints fold into the previous joint's `after` (leading ones
// into the first joint's `before`). Every link is attached to the frame of the chain link it
// hangs from (robot_description.hpp).

#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// The gripper as a robot file names it; `where` prefixes its errors ("robot file 'r.yaml': ").
struct RobotFileGripper {
  std::vector<std::string> joints;  // driven joints
  std::vector<double> closed, open;
  double max_opening_m = 0.08;
  std::string where;
};

struct UrdfDescription {
  RobotModel::Description model;  // joints, name (the URDF's), source, named config `zero`
  std::string root_link, tip_link;
  std::vector<RobotLink> links;  // every link, depth first from the root
  std::optional<Gripper> gripper;
};

// Errors start with "URDF '<source>': " (gripper errors with gripper->where).
Result<UrdfDescription> describe_urdf(
    const std::string& text, const std::string& source, const std::string& tip_link,
    const std::optional<RobotFileGripper>& gripper = std::nullopt);

// The whole file as text; "cannot open URDF file '<path>'" or "URDF '<path>': the file is empty".
Result<std::string> read_urdf_text(const std::string& path);

}  // namespace telear::core
