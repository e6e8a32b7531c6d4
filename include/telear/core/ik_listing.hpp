#pragma once
// Every inverse-kinematics solution of one tool pose, for any arm, as `telear kin ik` lists
// them: the closed form's eight for an arm of the PUMA class (ik_analytic.hpp), the closed
// form's existing branches (up to 8) for an arm of the UR class (ik_ur.hpp), every solution
// branch of another six-joint arm found by seeded restarts (ik_branches.hpp), and for a
// redundant arm -- which has infinitely many -- the one nearest the zero configuration
// (clamped into the limits) that follows the null-space preference (ik_redundant.hpp).

#include <Eigen/Geometry>
#include <string_view>

#include "telear/core/ik_analytic.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

struct IkListing {
  AnalyticIkResult result;   // status kOk or kSingular (with the message), the solutions
  bool closed_form = false;  // false: numeric (branches or the redundant arm's nearest)
};

// `config` (it must pass check_ik_config) selects closed-form solutions ("lun", "l", ...); an
// arm without a closed form refuses a non-empty one, saying why it has neither. Other errors:
// the pose is unreachable (the closed form's reason) or no numeric solution was found.
Result<IkListing> list_ik_solutions(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                                    std::string_view config = "");

}  // namespace telear::core
