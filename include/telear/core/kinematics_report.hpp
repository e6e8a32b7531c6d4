#pragma once
// What `telear kin` prints (docs/cli.md): the model's joints, limits and named
// configurations; the tool pose at a configuration; every IK solution of a pose
// (ik_listing.hpp); and the tour of the geometric model (`kin demo`). Text for operators
// (degrees and millimetres), JSON for scripts (radians and metres, 2-space indent, trailing
// newline), so that the console and tests read the same figures the command prints.

#include <Eigen/Geometry>
#include <string>

#include "telear/core/ik_listing.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// "  xyz = (0.4521, -0.1501, 0.4318) m   rpy = (0.000, 90.000, 0.000) deg\n".
std::string pose_line(const Eigen::Isometry3d& T);

// The joints table (limits in deg or mm) and the named configurations (deg; those outside
// the limits marked); JSON: name, dof, joints[] (SI limits), named_configurations.
std::string robot_info_text(const RobotModel& model);
std::string robot_info_json(const RobotModel& model);

// T_base_tool's rows, the pose line and a warning when q leaves the limits; JSON: T_base_tool
// and frames[] (row-major 4x4), q, within_limits.
std::string forward_kinematics_text(const RobotModel& model, const Eigen::VectorXd& q);
std::string forward_kinematics_json(const RobotModel& model, const Eigen::VectorXd& q);

// The solutions of `T_base_tool`, in degrees (revolute joints) with `degrees`, each marked
// within or outside the limits (2*pi equivalents considered) and singular; JSON: robot,
// method (analytic | numeric), status, message, units, solutions[].
std::string ik_listing_text(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                            const IkListing& listing, bool degrees);
std::string ik_listing_json(const RobotModel& model, const IkListing& listing, bool degrees);

// `kin demo`: the pose and manipulability at each named configuration and, for an arm with
// the closed form, its eight solutions there, the worst round trip |FK(IK(T)) - T| and which
// solution is the configuration itself.
std::string kinematics_tour_text(const RobotModel& model);

}  // namespace telear::core
