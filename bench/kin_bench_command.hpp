#pragma once
// `telear bench kin`: telear's kinematics timed against Orocos KDL on the same chain, in the
// same run, and printed as a table of ratios (docs/benchmarks.md):
//
//   operation | telear | KDL | KDL / telear | target | met
//
// for any robot --robot names (a DH table, a robot file or a URDF, with --tip and
// --package-path as every command that takes --robot): forward kinematics (all frames),
// incremental FK (the wrist joint changed), the Jacobian, and inverse kinematics over `poses`
// random reachable targets (solved %, mean and p99 time; cold start and seeded near the
// answer), each against KDL's ChainIkSolverPos_LMA from the same seeds. Which telear IK rows
// depend on the arm: the PUMA's closed form (all 8 solutions) and its numeric IK; a UR-class
// arm (ik_ur.hpp): its closed form (every branch, beside KDL's LMA), numeric IK,
// solve_ik_nearest through the closed form, and every branch by solve_ik_all and by the
// numeric search (search_ik_branches); another 6-joint arm: numeric IK and every branch
// (solve_ik_all, a seeded search); a redundant arm: numeric IK alone and with the
// null-space preference (solve_ik_nearest). The KDL chain of a DH robot is built from its
// table, that of a URDF robot by kdl_parser from the same URDF text.
// Times are thread CPU time, so that a busy shared machine inflates them less; the ratios are
// the figures to compare across machines. Sanity checks of the baseline are printed too:
// KDL's FK against telear's, and the closed forms' IK round trips.
//
// Built only with TELEAR_BUILD_BENCH (KDL is a benchmark-only dependency); main.cpp reports
// its absence otherwise.

#include <iosfwd>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

// --robot, --tip, --package-path (geometry/robot_selection.hpp; --missing-meshes is not
// offered: no meshes).
struct BenchKinOptions : geometry::RobotSelection {
  int poses = 10000;  // numeric IK targets (and FK sanity-check configurations)
  std::string json;   // also write the table as JSON to this file; empty: no
};

int run_bench_kin(const BenchKinOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
