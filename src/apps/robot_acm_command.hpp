#pragma once
// `telear robot acm`: the robot's allowed-collision matrix found by sampling (as MoveIt's
// setup assistant does; geometry/allowed_collisions_file.hpp), printed as the
// `allowed_collisions:` block of its robot file, or written to a file with -o. The robot
// file's own stored matrix is not consulted: this is how one is made or checked.
// Exit codes: 0 written, 2 bad input (one line on stderr).

#include <cstdint>
#include <iosfwd>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

struct RobotAcmOptions : geometry::RobotSelection {
  int samples = 2000;       // random configurations within the joint limits
  std::uint64_t seed = 13;  // the same matrix every run
  bool never = false;       // also allow the pairs in contact in no sample
  bool constant = true;     // also allow the pairs at a constant distance (--no-constant: not)
  double constant_tolerance_m = 1e-4;  // the largest distance range still constant
  std::string output;                  // -o FILE; empty: stdout
};

int run_robot_acm(const RobotAcmOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
