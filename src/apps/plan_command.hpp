#pragma once
// `telear plan check`: a saved plan (session/plan.hpp's YAML) checked for collisions along its
// timed trajectory against a workspace file and the robot itself (session/plan_collision.hpp).
// Exit codes: 0 collision-free, 1 a collision, 2 bad input (one line on stderr).

#include <iosfwd>
#include <string>

#include "apps/robot_arguments.hpp"

namespace telear::cli {

struct PlanCheckOptions : RobotArguments {
  std::string workspace;  // empty: the robot's shipped workspace
  std::string plan;
  bool json = false;
};

int run_plan_check(const PlanCheckOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
