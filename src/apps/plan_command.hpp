#pragma once
// `telear plan check`: a saved plan (session/plan.hpp's YAML) checked for collisions along its
// timed trajectory against a workspace file and the robot itself (session/plan_collision.hpp).
// Exit codes: 0 collision-free, 1 a collision, 2 bad input (one line on stderr).
// `telear plan hash`: its hash (below).

#include <iosfwd>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

struct PlanCheckOptions : geometry::RobotSelection {
  std::string workspace;  // empty: the robot's shipped workspace
  std::string plan;
  bool json = false;
  bool exact_meshes = false;  // mesh links' triangles instead of their parts' convex hulls
};

int run_plan_check(const PlanCheckOptions& options, std::ostream& out, std::ostream& err);

// `telear plan hash`: the plan's core::plan_hash (telear/core/plan_hash.hpp), the SHA-256 the
// plan message carries, computed in this process: the same plan hashed by any process gives
// the same 64 hex digits. Prints the hash alone on a line, or with --json
// {"plan_hash", "algorithm", "duration_s", "waypoints"}. Exit codes: 0, or 2 bad input.
struct PlanHashOptions : geometry::RobotSelection {
  std::string plan;
  bool json = false;
};

int run_plan_hash(const PlanHashOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
