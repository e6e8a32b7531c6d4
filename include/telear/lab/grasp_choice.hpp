#pragma once
// The grasp of a pick-and-place (docs/demo.md, step 4): the rotation of the gripper's link
// (link 6) in the base frame for a task whose every position the gripper's centre must reach.
//
// The gripper's centre (between the fingers, `grip_in_link_m` in link 6) goes to each task
// position with its fingers pointing down, tilted as little as the arm's limits allow, and
// spun about its own axis so that its marker side (+x of link 6) faces the cameras as
// squarely as possible (so the live registration check sees the marker). Candidates
//
//   R = Rz(heading) Ry(tilt) R_down Rz(spin),   R_down = diag(1, -1, -1),
//
// tilt 0..60 deg in 10 deg steps, heading 0..330 deg in 30 deg steps (one heading at tilt 0),
// spin 0..330 deg in 30 deg steps, are scored by tilt_deg + away_deg, away_deg the angle
// between R's +x and the direction from the first task position to the cameras. In ascending
// score, the first candidate whose every task position, visited in order from q_start (each
// seeded by the previous), has an IK solution within the joint limits
// (include/telear/core/inverse_kinematics.hpp) wins; with `contact` given, also none of
// those solutions may touch the scene (the nearest IK branch is the one the ghost takes, so
// a candidate whose branch goes through the table is passed over: the PUMA within its elbow
// range reaches a box near its pedestal only elbow-down, through the table).

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::lab {

struct GraspRequest {
  std::vector<Eigen::Vector3d> grip_positions_base_m;        // the task's gripper-centre positions
  Eigen::Vector3d grip_in_link_m = Eigen::Vector3d::Zero();  // gripper centre in link 6
  Eigen::VectorXd q_start;                                   // rad or m, the arm now
  Eigen::Vector3d camera_base_m = Eigen::Vector3d::Zero();   // where the cameras are
  std::string object_name = "the box";                       // for the error message
  // Optional: what the arm at q touches ("link3 – table_top (79.5 mm deep)"), nullopt when
  // clear. Unset: no scene check.
  std::function<std::optional<std::string>(const Eigen::VectorXd& q)> contact;
};

struct GraspChoice {
  Eigen::Matrix3d R_base_link = Eigen::Matrix3d::Identity();
  int tilt_deg = 0;  // from straight down
  int away_deg = 0;  // the marker side's angle away from facing the cameras (rounded)

  // The tool pose (for core's IK / Cartesian targets) that puts the gripper's centre at
  // `grip_position_base_m` with this rotation.
  Eigen::Isometry3d T_base_tool(const core::RobotModel& model,
                                const Eigen::Vector3d& grip_in_link_m,
                                const Eigen::Vector3d& grip_position_base_m) const;
  // "gripper tilted 10 deg, its marker 35 deg away from facing the cameras"
  std::string note() const;
};

// Errors: an empty task, a q_start of the wrong size, or no candidate reaches every position
// within the joint limits (the message names the object and its first position), or, with
// `contact`, every candidate that reaches them touches the scene (the message names the
// least tilted one's first contact and where).
Result<GraspChoice> choose_grasp(const core::RobotModel& model, const GraspRequest& request);

}  // namespace telear::lab
