#include "bench/kin_bench_command.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/jacobian.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <ostream>
#include <thread>
#include <vector>

#include "bench/cpu_timing.hpp"
#include "bench/ik_timing.hpp"
#include "bench/kdl_chain.hpp"
#include "bench/kin_table.hpp"
#include "bench/kin_workload.hpp"
#include "telear/core/ik_analytic.hpp"
#include "telear/core/ik_numeric.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/robot_loader.hpp"

namespace telear::cli {
namespace {

constexpr int kInputs = 1024;  // inputs cycled through by the per-call benchmarks (power of 2)

using bench::best_ns_per_call;
using bench::cpu_seconds;
using bench::IkStats;
using bench::join_met;
using bench::keep;
using bench::kNone;
using bench::met_ratio;
using bench::met_time;
using bench::print_table;
using bench::Row;
using bench::time_numeric_ik;

}  // namespace

int run_bench_kin(const BenchKinOptions& options, std::ostream& out, std::ostream& err) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (options.poses < 100) {
    err << "telear bench kin: --poses must be at least 100, got " << options.poses << "\n";
    return 2;
  }
  auto loaded = core::load_robot(options.robot);
  if (!loaded) {
    err << "telear bench kin: " << loaded.error().message << "\n";
    return 2;
  }
  const core::RobotModel& model = **loaded;
  auto built = bench::kdl_chain_from_dh(model);
  if (!built) {
    err << "telear bench kin: " << built.error().message << "\n";
    return 2;
  }
  const KDL::Chain chain = *built;  // KDL's solvers keep a reference: it outlives them
  auto geometry = core::puma_geometry(model);
  if (!geometry) {
    err << "telear bench kin: " << geometry.error().message << "\n";
    return 2;
  }
  const int n = model.dof();
  const auto nj = chain.getNrOfJoints();

  std::ofstream json_file;
  if (!options.json.empty()) {
    json_file.open(options.json);
    if (!json_file) {
      err << "telear bench kin: --json: cannot write '" << options.json << "'\n";
      return 2;
    }
  }

  char line[512];
  std::snprintf(line, sizeof line,
                "telear bench kin: robot %s, %d numeric IK targets, %u hardware threads%s\n",
                model.name().c_str(), options.poses, std::thread::hardware_concurrency(),
#ifdef NDEBUG
                ""
#else
                " (assertions on: not a Release build, times are not representative)"
#endif
  );
  out << line;
  out << "CPU time of this thread per call; per-call rows: best of 15 batches of 20 ms over "
      << kInputs << " random configurations\n\n";
  out.flush();

  // Inputs: random configurations within the limits, and reachable targets made from others.
  const std::vector<Eigen::VectorXd> qs = bench::random_configurations(model, kInputs, 1);
  std::vector<KDL::JntArray> qs_kdl;
  for (const auto& q : qs) qs_kdl.push_back(bench::to_kdl(q));
  const std::vector<bench::IkCase> cases = bench::make_ik_cases(model, options.poses, 2);

  // Sanity check of the baseline: KDL's frames equal telear's on every target's q_true.
  core::KinematicsData data(model);
  KDL::ChainFkSolverPos_recursive kdl_fk(chain);
  std::vector<KDL::Frame> kdl_frames(chain.getNrOfSegments());
  double fk_max_diff = 0.0;
  for (const auto& c : cases) {
    core::forward_kinematics(model, data, c.q_true);
    kdl_fk.JntToCart(bench::to_kdl(c.q_true), kdl_frames);
    for (int i = 0; i < n; ++i) {
      const Eigen::Isometry3d T_kdl = bench::from_kdl(kdl_frames[static_cast<size_t>(i)]);
      const Eigen::Isometry3d& T = i + 1 == n ? data.T_base_tool : data.T_base_link[i + 1];
      fk_max_diff = std::max(fk_max_diff, (T_kdl.matrix() - T.matrix()).cwiseAbs().maxCoeff());
    }
  }

  std::vector<Row> rows;
  const int mask = kInputs - 1;

  // Forward kinematics, all frames.
  const double fk_telear = best_ns_per_call([&](long i) {
    core::forward_kinematics(model, data, qs[static_cast<size_t>(i & mask)]);
    keep(data.T_base_tool);
  });
  const double fk_kdl = best_ns_per_call([&](long i) {
    kdl_fk.JntToCart(qs_kdl[static_cast<size_t>(i & mask)], kdl_frames);
    keep(kdl_frames[0]);
  });
  rows.push_back({"FK, all frames", "ns", fk_telear, fk_kdl, "<= 100 ns, >= 10x KDL",
                  join_met(met_time(fk_telear, 100.0, "ns"), met_ratio(fk_kdl / fk_telear, 10.0))});

  // Incremental FK: the wrist joint (5 of 6) changes; KDL has no incremental form, so its
  // figure is full FK, what a KDL user pays for the same update.
  const int wrist = std::max(0, n - 2);
  core::forward_kinematics(model, data, qs[0]);
  const double incremental = best_ns_per_call([&](long i) {
    core::set_joint(model, data, wrist, qs[static_cast<size_t>(i & mask)][wrist]);
    keep(data.T_base_tool);
  });
  rows.push_back({"FK, joint " + std::to_string(wrist + 1) + " changed (incremental)", "ns",
                  incremental, fk_kdl, "", ""});

  // Jacobian at a new configuration: FK + J, the work of KDL's JntToJac.
  core::Jacobian J(6, n);
  const double jac_telear = best_ns_per_call([&](long i) {
    core::forward_kinematics(model, data, qs[static_cast<size_t>(i & mask)]);
    core::geometric_jacobian(model, data, core::JacobianFrame::kBase, J);
    keep(J(0, 0));
  });
  KDL::ChainJntToJacSolver kdl_jac(chain);
  KDL::Jacobian J_kdl(nj);
  const double jac_kdl = best_ns_per_call([&](long i) {
    kdl_jac.JntToJac(qs_kdl[static_cast<size_t>(i & mask)], J_kdl);
    keep(J_kdl(0, 0));
  });
  rows.push_back({"Jacobian (with FK)", "ns", jac_telear, jac_kdl, "", ""});

  // Analytic IK, all 8 solutions: the allocation-free core and the labelled API.
  core::PumaIkSolutions solutions;
  const int ik_inputs = std::min<int>(kInputs, static_cast<int>(cases.size()));
  auto target = [&](long i) -> const Eigen::Isometry3d& {
    return cases[static_cast<size_t>(i % ik_inputs)].T_base_tool;
  };
  const double analytic = best_ns_per_call([&](long i) {
    core::solve_puma_ik(*geometry, target(i), solutions);
    keep(solutions.q[0]);
  });
  rows.push_back({"analytic IK, all 8 (solve_puma_ik)", "ns", analytic, kNone, "<= 1000 ns",
                  met_time(analytic, 1000.0, "ns")});
  const double analytic_api = best_ns_per_call([&](long i) {
    const core::AnalyticIkResult r = core::solve_analytic_ik(model, *geometry, target(i));
    keep(r.solutions.size());
  });
  rows.push_back({"analytic IK, all 8 (labelled API)", "ns", analytic_api, kNone, "", ""});

  // Round trip of the analytic solutions (non-singular ones) over every target.
  double analytic_round_trip = 0.0;
  int unreachable = 0;
  for (const auto& c : cases) {
    core::solve_puma_ik(*geometry, c.T_base_tool, solutions);
    if (!solutions.reachable()) {
      ++unreachable;
      continue;
    }
    for (int s = 0; s < core::PumaIkSolutions::kCount; ++s) {
      if (solutions.singularity[static_cast<size_t>(s)] != 0) continue;
      core::forward_kinematics(model, data, solutions.q[static_cast<size_t>(s)]);
      analytic_round_trip =
          std::max(analytic_round_trip,
                   (data.T_base_tool.matrix() - c.T_base_tool.matrix()).cwiseAbs().maxCoeff());
    }
  }

  // Numeric IK: telear's Levenberg-Marquardt against KDL's ChainIkSolverPos_LMA (defaults).
  core::NumericIkSolver solver(model);
  const double tol_p = solver.options().position_tolerance_m;
  const double tol_r = solver.options().orientation_tolerance_rad;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  KDL::ChainIkSolverPos_LMA lma(chain);
  const KDL::JntArray zero_kdl(nj);
  KDL::JntArray q_kdl(nj);
  std::vector<KDL::Frame> targets_kdl;
  std::vector<KDL::JntArray> seeds_kdl;
  for (const auto& c : cases) {
    targets_kdl.push_back(bench::to_kdl(c.T_base_tool));
    seeds_kdl.push_back(bench::to_kdl(c.q_near));
  }
  struct Outcome {
    bool success;
    Eigen::VectorXd q;
  };
  const double verify_p = 1.5 * tol_p;  // telear's answers are checked by FK at its tolerance
  const double verify_r = 1.5 * tol_r;
  auto telear_ik = [&](bool seeded) {
    return time_numeric_ik(
        model, cases,
        [&](size_t k) {
          const core::NumericIkResult r =
              solver.solve(cases[k].T_base_tool, seeded ? cases[k].q_near : zero);
          return Outcome{r.success, r.q};
        },
        verify_p, verify_r);
  };
  auto kdl_ik = [&](bool seeded) {
    // KDL's defaults converge at |L (dp, dR)| < 1e-5 with L = (1, 1, 1, 0.01, 0.01, 0.01),
    // looser than telear's 1e-6 m and 1e-6 rad: its answers are checked at 1e-5 m, 1e-3 rad.
    return time_numeric_ik(
        model, cases,
        [&](size_t k) {
          const int rc = lma.CartToJnt(seeded ? seeds_kdl[k] : zero_kdl, targets_kdl[k], q_kdl);
          return Outcome{rc >= 0, q_kdl.data};
        },
        1e-5, 1e-3);
  };
  struct IkRun {
    const char* name;
    IkStats telear, kdl;
  };
  std::vector<IkRun> ik_runs = {{"cold start, q = 0", telear_ik(false), kdl_ik(false)},
                                {"seeded near the answer", telear_ik(true), kdl_ik(true)}};
  for (const IkRun& run : ik_runs) {
    const bool cold = run.name[0] == 'c';
    const std::string name = std::string("numeric IK, ") + run.name;
    rows.push_back({name + ": solved", "%", run.telear.solved_percent, run.kdl.solved_percent,
                    cold ? ">= 99.9 %" : "",
                    cold ? (run.telear.solved_percent >= 99.9 ? "yes" : "no") : ""});
    rows.push_back({name + ": mean", "us", run.telear.mean_us, run.kdl.mean_us,
                    cold ? ">= 10x KDL" : "",
                    cold ? met_ratio(run.kdl.mean_us / run.telear.mean_us, 10.0) : ""});
    rows.push_back({name + ": p99", "us", run.telear.p99_us, run.kdl.p99_us, "", ""});
  }

  print_table(rows, out);
  out << "\n";
  std::snprintf(line, sizeof line,
                "check: KDL FK vs telear FK, all %d frames of %d configurations: max |difference| "
                "%.2g\n",
                n, options.poses, fk_max_diff);
  out << line;
  std::snprintf(line, sizeof line,
                "check: analytic IK round trip FK(IK(T)) vs T, non-singular solutions of %d "
                "targets: max |difference| %.2g (%d unreachable)\n",
                options.poses, analytic_round_trip, unreachable);
  out << line;
  for (const IkRun& run : ik_runs) {
    std::snprintf(line, sizeof line,
                  "note: numeric IK %s: reported solved but outside the joint limits: telear "
                  "%d, KDL %d (KDL's LMA ignores limits); failing the FK check: telear %d, "
                  "KDL %d\n",
                  run.name, run.telear.outside_limits, run.kdl.outside_limits,
                  run.telear.unverified, run.kdl.unverified);
    out << line;
  }
  std::snprintf(line, sizeof line,
                "note: solved = converged, FK within tolerance and joints within limits; telear "
                "converges at %.0e m and %.0e rad, KDL's LMA at its defaults (weighted error < "
                "1e-5, rotation weight 0.01; checked at 1e-5 m, 1e-3 rad)\n",
                tol_p, tol_r);
  out << line;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::snprintf(line, sizeof line, "ran in %.1f s\n", wall);
  out << line;

  if (json_file) {
    nlohmann::json j;
    j["robot"] = model.name();
    j["poses"] = options.poses;
    j["time"] = "thread CPU time";
    for (const Row& r : rows) {
      auto number = [](double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); };
      j["rows"].push_back({{"operation", r.operation},
                           {"unit", r.unit},
                           {"telear", number(r.telear)},
                           {"kdl", number(r.kdl)},
                           {"kdl_over_telear", number(r.ratio())},
                           {"target", r.target},
                           {"met", r.met}});
    }
    j["fk_max_difference_vs_kdl"] = fk_max_diff;
    j["analytic_round_trip_max_difference"] = analytic_round_trip;
    json_file << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace telear::cli
