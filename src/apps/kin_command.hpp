#pragma once
// `telear kin ...`: the arm's geometric model from the command line. Each function returns
// the process exit code; results go to `out`, one-line errors to `err`.

#include <iosfwd>
#include <optional>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

struct KinOptions : geometry::RobotSelection {
  std::string q;                    // fk: comma-separated joint values
  std::optional<std::string> T;     // ik: 16 numbers, row-major
  std::optional<std::string> pose;  // ik: x,y,z,roll,pitch,yaw (m, rad or deg with --deg)
  std::string config;               // ik: e.g. "lun"; empty = all solutions
  bool degrees = false;             // angles given and printed in degrees
  bool json = false;
};

int run_kin_info(const KinOptions& options, std::ostream& out, std::ostream& err);
int run_kin_fk(const KinOptions& options, std::ostream& out, std::ostream& err);
int run_kin_ik(const KinOptions& options, std::ostream& out, std::ostream& err);
// The README's first command until `telear demo` exists: FK at every named configuration,
// analytic IK back to all eight solutions, and the round-trip error.
int run_kin_demo(const KinOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
