#include "bench/kin_bench_command.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/jacobian.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <ostream>
#include <thread>
#include <utility>
#include <vector>

#include "bench/cpu_timing.hpp"
#include "bench/ik_timing.hpp"
#include "bench/kdl_chain.hpp"
#include "bench/kin_table.hpp"
#include "bench/kin_workload.hpp"
#include "telear/core/ik_analytic.hpp"
#include "telear/core/ik_branches.hpp"
#include "telear/core/ik_numeric.hpp"
#include "telear/core/ik_ur.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/robot_description.hpp"

namespace telear::cli {
namespace {

constexpr int kInputs = 1024;  // inputs cycled through by the per-call benchmarks (power of 2)
// solve_ik_all runs ~100 LM solves per target: timed on at most this many of the targets.
constexpr int kBranchTargets = 1000;

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

struct Outcome {
  bool success;
  Eigen::VectorXd q;
};

// The cold-start seed of the numeric IK rows and its name: q = 0 where it is within the
// limits (the PUMA's qz); otherwise the robot's named "home" or "ready" configuration (arm7's
// joint 4 excludes 0), else the middle of every range.
std::pair<Eigen::VectorXd, std::string> cold_start(const core::RobotModel& model) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.dof());
  if (core::within_limits(model, zero)) return {zero, "q = 0"};
  for (const char* name : {"home", "ready"}) {
    if (auto q = model.named_configuration(name)) return {*q, std::string("q = ") + name};
  }
  Eigen::VectorXd mid(model.dof());
  for (int i = 0; i < model.dof(); ++i) {
    const double lo = model.lower_limits()[i], hi = model.upper_limits()[i];
    mid[i] = std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi) : 0.0;
  }
  return {mid, "q = mid-range"};
}

}  // namespace

int run_bench_kin(const BenchKinOptions& options, std::ostream& out, std::ostream& err) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (options.poses < 100) {
    err << "telear bench kin: --poses must be at least 100, got " << options.poses << "\n";
    return 2;
  }
  auto description = core::load_robot_description(options.robot_spec());
  if (!description) {
    err << "telear bench kin: " << description.error().message << "\n";
    return 2;
  }
  const core::RobotModel& model = *description->model;
  // A DH robot's chain from its table (one segment per joint: every link frame compared); a
  // URDF robot's from kdl_parser (fixed joints are segments too: the tool pose compared).
  const bool from_dh = description->urdf_text.empty();
  auto built = from_dh ? bench::kdl_chain_from_dh(model) : bench::kdl_chain_from_urdf(*description);
  if (!built) {
    err << "telear bench kin: " << built.error().message << "\n";
    return 2;
  }
  const KDL::Chain chain = *built;  // KDL's solvers keep a reference: it outlives them
  // The closed forms: the PUMA's (DH tables only) and the UR class's (any file).
  auto geometry = core::puma_geometry(model);
  const int n = model.dof();
  std::optional<core::UrGeometry> ur;
  if (!geometry && n == 6) {
    if (auto g = core::ur_geometry(model)) ur = *g;
  }
  const auto nj = chain.getNrOfJoints();
  if (static_cast<int>(nj) != n) {
    err << "telear bench kin: KDL's chain has " << nj << " joints, telear's " << n << "\n";
    return 2;
  }

  std::ofstream json_file;
  if (!options.json.empty()) {
    json_file.open(options.json);
    if (!json_file) {
      err << "telear bench kin: --json: cannot write '" << options.json << "'\n";
      return 2;
    }
  }

  double load[3] = {0, 0, 0};
  const bool has_load = getloadavg(load, 3) == 3;
  char line[512];
  std::snprintf(line, sizeof line,
                "telear bench kin: robot %s (%d joints%s%s), %d numeric IK targets, %u hardware "
                "threads%s\n",
                model.name().c_str(), n, from_dh ? ", DH" : ", URDF tip ",
                from_dh ? "" : description->tip_link.c_str(), options.poses,
                std::thread::hardware_concurrency(),
#ifdef NDEBUG
                ""
#else
                " (assertions on: not a Release build, times are not representative)"
#endif
  );
  out << line;
  if (has_load) {
    std::snprintf(line, sizeof line, "load average %.2f %.2f %.2f at the start\n", load[0], load[1],
                  load[2]);
    out << line;
  }
  out << "CPU time of this thread per call; per-call rows: best of 15 batches of 20 ms over "
      << kInputs << " random configurations\n\n";
  out.flush();

  // Inputs: random configurations within the limits, and reachable targets made from others.
  const std::vector<Eigen::VectorXd> qs = bench::random_configurations(model, kInputs, 1);
  std::vector<KDL::JntArray> qs_kdl;
  for (const auto& q : qs) qs_kdl.push_back(bench::to_kdl(q));
  const std::vector<bench::IkCase> cases = bench::make_ik_cases(model, options.poses, 2);

  // Sanity check of the baseline: KDL's frames equal telear's on every target's q_true (every
  // link frame for a DH chain, the tool pose for a URDF one).
  core::KinematicsData data(model);
  KDL::ChainFkSolverPos_recursive kdl_fk(chain);
  std::vector<KDL::Frame> kdl_frames(chain.getNrOfSegments());
  double fk_max_diff = 0.0;
  for (const auto& c : cases) {
    core::forward_kinematics(model, data, c.q_true);
    if (from_dh) {
      kdl_fk.JntToCart(bench::to_kdl(c.q_true), kdl_frames);
      for (int i = 0; i < n; ++i) {
        const Eigen::Isometry3d T_kdl = bench::from_kdl(kdl_frames[static_cast<size_t>(i)]);
        const Eigen::Isometry3d& T = i + 1 == n ? data.T_base_tool : data.T_base_link[i + 1];
        fk_max_diff = std::max(fk_max_diff, (T_kdl.matrix() - T.matrix()).cwiseAbs().maxCoeff());
      }
    } else {
      KDL::Frame tip;
      kdl_fk.JntToCart(bench::to_kdl(c.q_true), tip);
      fk_max_diff = std::max(
          fk_max_diff,
          (bench::from_kdl(tip).matrix() - data.T_base_tool.matrix()).cwiseAbs().maxCoeff());
    }
  }

  std::vector<Row> rows;
  const int mask = kInputs - 1;

  // Forward kinematics, all frames. The FK targets were set for the PUMA (DH).
  const double fk_telear = best_ns_per_call([&](long i) {
    core::forward_kinematics(model, data, qs[static_cast<size_t>(i & mask)]);
    keep(data.T_base_tool);
  });
  const double fk_kdl = best_ns_per_call([&](long i) {
    kdl_fk.JntToCart(qs_kdl[static_cast<size_t>(i & mask)], kdl_frames);
    keep(kdl_frames[0]);
  });
  rows.push_back(
      {"FK, all frames", "ns", fk_telear, fk_kdl, from_dh ? "<= 100 ns, >= 10x KDL" : "",
       from_dh ? join_met(met_time(fk_telear, 100.0, "ns"), met_ratio(fk_kdl / fk_telear, 10.0))
               : ""});

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

  // Analytic IK, all 8 solutions: the allocation-free core and the labelled API, and the
  // round trip of the non-singular solutions over every target.
  double analytic_round_trip = 0.0;
  int unreachable = 0;
  if (geometry) {
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
  }

  // The UR class's closed form, every branch: the allocation-free core and the labelled API
  // (which checks each branch by FK and polishes it where it misses by more than 1e-12), and
  // the round trip of every branch over every target. Its KDL column is KDL's LMA from the
  // cold start (one solution, to KDL's tolerance), timed below in this same run: the
  // comparison a user choosing between them makes.
  double ur_round_trip = 0.0;
  int ur_unreachable = 0;
  double ur_branches = 0.0;
  double ur_core_ns = 0.0, ur_api_ns = 0.0;
  if (ur) {
    core::UrIkSolutions solutions;
    const int ik_inputs = std::min<int>(kInputs, static_cast<int>(cases.size()));
    auto target = [&](long i) -> const Eigen::Isometry3d& {
      return cases[static_cast<size_t>(i % ik_inputs)].T_base_tool;
    };
    ur_core_ns = best_ns_per_call([&](long i) {
      core::solve_ur_ik(*ur, target(i), solutions);
      keep(solutions.q[0]);
    });
    ur_api_ns = best_ns_per_call([&](long i) {
      const core::AnalyticIkResult r = core::solve_ur_analytic_ik(model, *ur, target(i));
      keep(r.solutions.size());
    });
    int listed = 0;
    for (const auto& c : cases) {
      const core::AnalyticIkResult r = core::solve_ur_analytic_ik(model, *ur, c.T_base_tool);
      if (r.status == core::IkStatus::kUnreachable) {
        ++ur_unreachable;
        continue;
      }
      for (const core::IkSolution& s : r.solutions) {
        ++listed;
        core::forward_kinematics(model, data, s.q);
        ur_round_trip =
            std::max(ur_round_trip,
                     (data.T_base_tool.matrix() - c.T_base_tool.matrix()).cwiseAbs().maxCoeff());
      }
    }
    ur_branches = static_cast<double>(listed) / static_cast<double>(cases.size());
  }

  // Numeric IK: telear's Levenberg-Marquardt (and, for a redundant arm, its null-space
  // preference) against KDL's ChainIkSolverPos_LMA (defaults), from the same seeds.
  core::NumericIkSolver solver(model);
  const double tol_p = solver.options().position_tolerance_m;
  const double tol_r = solver.options().orientation_tolerance_rad;
  const std::pair<Eigen::VectorXd, std::string> cold_seed = cold_start(model);
  const Eigen::VectorXd& cold_q = cold_seed.first;
  KDL::ChainIkSolverPos_LMA lma(chain);
  const KDL::JntArray cold_kdl = bench::to_kdl(cold_q);
  KDL::JntArray q_kdl(nj);
  std::vector<KDL::Frame> targets_kdl;
  std::vector<KDL::JntArray> seeds_kdl;
  for (const auto& c : cases) {
    targets_kdl.push_back(bench::to_kdl(c.T_base_tool));
    seeds_kdl.push_back(bench::to_kdl(c.q_near));
  }
  const double verify_p = 1.5 * tol_p;  // telear's answers are checked by FK at its tolerance
  const double verify_r = 1.5 * tol_r;
  auto seed = [&](size_t k, bool seeded) -> const Eigen::VectorXd& {
    return seeded ? cases[k].q_near : cold_q;
  };
  auto lm_ik = [&](bool seeded) {
    return time_numeric_ik(
        model, cases,
        [&](size_t k) {
          const core::NumericIkResult r = solver.solve(cases[k].T_base_tool, seed(k, seeded));
          return Outcome{r.success, r.q};
        },
        verify_p, verify_r);
  };
  // solve_ik_nearest: for a redundant arm LM at 1e-9, then the null-space preference (near
  // the seed: the smallest motion) with the pose kept to 1e-10.
  auto nearest_ik = [&](bool seeded) {
    return time_numeric_ik(
        model, cases,
        [&](size_t k) {
          auto r = core::solve_ik_nearest(model, cases[k].T_base_tool, seed(k, seeded));
          return r ? Outcome{true, r->q} : Outcome{false, seed(k, seeded)};
        },
        verify_p, verify_r);
  };
  auto kdl_ik = [&](bool seeded) {
    // KDL's defaults converge at |L (dp, dR)| < 1e-5 with L = (1, 1, 1, 0.01, 0.01, 0.01),
    // looser than telear's 1e-6 m and 1e-6 rad: its answers are checked at 1e-5 m, 1e-3 rad.
    return time_numeric_ik(
        model, cases,
        [&](size_t k) {
          const int rc = lma.CartToJnt(seeded ? seeds_kdl[k] : cold_kdl, targets_kdl[k], q_kdl);
          return Outcome{rc >= 0, q_kdl.data};
        },
        1e-5, 1e-3);
  };
  struct IkRun {
    std::string name;
    IkStats telear, kdl;
    bool goals;  // the goals apply to this row
  };
  const IkStats kdl_cold = kdl_ik(false);
  const IkStats kdl_seeded = kdl_ik(true);
  const std::string cold = "cold start, " + cold_seed.second;
  if (ur) {
    // KDL's LMA from the cold start beside the closed form's every branch (see above).
    rows.push_back({"closed-form IK, all branches (solve_ur_ik) vs KDL LMA " + cold, "ns",
                    ur_core_ns, 1000.0 * kdl_cold.mean_us, "", ""});
    rows.push_back({"closed-form IK, all branches (labelled API)", "ns", ur_api_ns, kNone, "", ""});
  }
  std::vector<IkRun> ik_runs;
  if (n <= 6) {
    // The PUMA's rows keep their names ("numeric IK, cold start, q = 0").
    ik_runs.push_back({"numeric IK, " + cold, lm_ik(false), kdl_cold, true});
    ik_runs.push_back({"numeric IK, seeded near the answer", lm_ik(true), kdl_seeded, false});
    if (ur) {
      // What motion commands call: the closed form's nearest branch within the limits.
      ik_runs.push_back({"closed-form IK nearest (solve_ik_nearest), " + cold, nearest_ik(false),
                         kdl_cold, false});
    }
  } else {
    ik_runs.push_back({"numeric IK (LM alone), " + cold, lm_ik(false), kdl_cold, true});
    ik_runs.push_back(
        {"redundant IK (LM + null space), " + cold, nearest_ik(false), kdl_cold, true});
    ik_runs.push_back({"numeric IK (LM alone), seeded near", lm_ik(true), kdl_seeded, false});
    ik_runs.push_back(
        {"redundant IK (LM + null space), seeded near", nearest_ik(true), kdl_seeded, false});
  }
  // The goals: >= 99.9 % solved and >= 10x KDL for every arm; a redundant arm's
  // mean also <= 50 us.
  const bool redundant = n > 6;
  for (const IkRun& run : ik_runs) {
    rows.push_back({run.name + ": solved", "%", run.telear.solved_percent, run.kdl.solved_percent,
                    run.goals ? ">= 99.9 %" : "",
                    run.goals ? (run.telear.solved_percent >= 99.9 ? "yes" : "no") : ""});
    std::string target, met;
    if (run.goals) {
      const std::string ratio = met_ratio(run.kdl.mean_us / run.telear.mean_us, 10.0);
      target = redundant ? "<= 50 us, >= 10x KDL" : ">= 10x KDL";
      met = redundant ? join_met(met_time(run.telear.mean_us, 50.0, "us"), ratio) : ratio;
    }
    rows.push_back({run.name + ": mean", "us", run.telear.mean_us, run.kdl.mean_us, target, met});
    rows.push_back({run.name + ": p99", "us", run.telear.p99_us, run.kdl.p99_us, "", ""});
  }

  // Every branch of a 6-joint arm other than the PUMA (solve_ik_all: the closed form of a
  // UR-class arm, else ~100 seeded LM solves), and for a UR-class arm the numeric search as
  // well (search_ik_branches, what solve_ik_all did before): solved when some listed branch
  // within the limits reaches the target. KDL has no counterpart.
  int branch_targets = 0;
  double branches_found = 0.0, branches_searched = 0.0;
  if (n == 6 && !geometry) {
    branch_targets = std::min<int>(kBranchTargets, static_cast<int>(cases.size()));
    const std::vector<bench::IkCase> some(cases.begin(), cases.begin() + branch_targets);
    const auto every_branch = [&](bool search, double& per_target) {
      int listed = 0;
      const IkStats stats = time_numeric_ik(
          model, some,
          [&](size_t k) {
            auto r = search ? core::search_ik_branches(model, some[k].T_base_tool)
                            : core::solve_ik_all(model, some[k].T_base_tool);
            if (!r) return Outcome{false, cold_q};
            listed += static_cast<int>(r->size());
            for (const core::IkSolution& s : *r) {
              if (s.within_limits) return Outcome{true, s.q};
            }
            return Outcome{false, cold_q};
          },
          verify_p, verify_r);
      per_target = static_cast<double>(listed) / branch_targets;
      return stats;
    };
    const std::string targets = std::to_string(branch_targets) + " targets";
    const IkStats all = every_branch(false, branches_found);
    const std::string name = "every branch (solve_ik_all), " + targets;
    rows.push_back({name + ": solved", "%", all.solved_percent, kNone, "", ""});
    rows.push_back({name + ": mean", "us", all.mean_us, kNone, "", ""});
    if (ur) {
      const IkStats searched = every_branch(true, branches_searched);
      const std::string by_search = "every branch by search (search_ik_branches), " + targets;
      rows.push_back({by_search + ": solved", "%", searched.solved_percent, kNone, "", ""});
      rows.push_back({by_search + ": mean", "us", searched.mean_us, kNone, "", ""});
    }
  }

  print_table(rows, out);
  out << "\n";
  if (from_dh) {
    std::snprintf(line, sizeof line,
                  "check: KDL FK vs telear FK, all %d frames of %d configurations: max "
                  "|difference| %.2g\n",
                  n, options.poses, fk_max_diff);
  } else {
    std::snprintf(line, sizeof line,
                  "check: KDL FK (kdl_parser chain %s -> %s) vs telear FK, tool pose of %d "
                  "configurations: max |difference| %.2g\n",
                  description->root_link.c_str(), description->tip_link.c_str(), options.poses,
                  fk_max_diff);
  }
  out << line;
  if (geometry) {
    std::snprintf(line, sizeof line,
                  "check: analytic IK round trip FK(IK(T)) vs T, non-singular solutions of %d "
                  "targets: max |difference| %.2g (%d unreachable)\n",
                  options.poses, analytic_round_trip, unreachable);
    out << line;
  }
  if (ur) {
    std::snprintf(line, sizeof line,
                  "check: UR closed-form IK round trip FK(IK(T)) vs T, every branch of %d "
                  "targets (%.2f per target): max |difference| %.2g (%d unreachable)\n",
                  options.poses, ur_branches, ur_round_trip, ur_unreachable);
    out << line;
    out << "note: the closed form's KDL column is ChainIkSolverPos_LMA from the cold start "
           "(one solution), timed in this run; the closed form lists every branch\n";
  }
  if (branch_targets > 0) {
    std::snprintf(line, sizeof line,
                  "note: solve_ik_all listed %.2f branches per target on average (within the "
                  "limits or not)%s\n",
                  branches_found, ur ? " by the closed form" : "");
    out << line;
    if (ur) {
      std::snprintf(line, sizeof line,
                    "note: search_ik_branches listed %.2f branches per target on average\n",
                    branches_searched);
      out << line;
    }
  }
  for (const IkRun& run : ik_runs) {
    std::snprintf(line, sizeof line,
                  "note: %s: reported solved but outside the joint limits: telear %d, KDL %d "
                  "(KDL's LMA ignores limits); failing the FK check: telear %d, KDL %d\n",
                  run.name.c_str(), run.telear.outside_limits, run.kdl.outside_limits,
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
    j["tip"] = description->tip_link;
    j["poses"] = options.poses;
    j["time"] = "thread CPU time";
    if (has_load) j["load_average"] = {load[0], load[1], load[2]};
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
    if (geometry) j["analytic_round_trip_max_difference"] = analytic_round_trip;
    if (ur) j["ur_closed_form_round_trip_max_difference"] = ur_round_trip;
    json_file << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace telear::cli
