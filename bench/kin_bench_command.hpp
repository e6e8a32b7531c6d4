#pragma once
// `telear bench kin`: telear's kinematics timed against Orocos KDL on the same chain, in the
// same run, and printed as a table of ratios (docs/benchmarks.md):
//
//   operation | telear | KDL | KDL / telear | target | met
//
// for forward kinematics (all frames), incremental FK (the wrist joint changed), the
// Jacobian, analytic IK (all 8 solutions) and numeric IK over `poses` random reachable
// targets (solved %, mean and p99 time; cold start from q = 0 and seeded near the answer).
// Times are thread CPU time, so that a busy shared machine inflates them less; the ratios are
// the figures to compare across machines. Two sanity checks of the baseline are printed
// too: KDL's FK against telear's, and the analytic IK round trip.
//
// Built only with TELEAR_BUILD_BENCH (KDL is a benchmark-only dependency); main.cpp reports
// its absence otherwise.

#include <iosfwd>
#include <string>

namespace telear::cli {

struct BenchKinOptions {
  std::string robot = "puma560";  // needs a DH table (the KDL chain is built from it)
  int poses = 10000;              // numeric IK targets (and FK sanity-check configurations)
  std::string json;               // also write the table as JSON to this file; empty: no
};

int run_bench_kin(const BenchKinOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
