// The 7-DOF benchmark (docs/benchmarks.md, "Redundant arm"): inverse kinematics of the shipped
// 7-joint arm (data/robots/arm7.yaml: a Panda-type arm, tip tcp) over random reachable poses,
// telear against Orocos KDL's ChainIkSolverPos_LMA in the same run, and forward kinematics
// against KDL's.
//
//   build/bench/redundant_ik_bench [poses] [robot]      (default 10,000 and arm7)
//
// The KDL chain is built by kdl_parser from the same URDF text (bench/kdl_chain.hpp), so the
// baseline shares no parsing code with telear. `telear bench kin --robot arm7` prints the same
// comparison inside the CLI; this program adds the rest-pose preference and stays a plain
// executable that a profiler can run.
//
// Targets: T = FK(q_true), q_true uniform within the limits (bench/kin_workload.hpp). Both
// solvers start from the robot's "ready" configuration (q = 0 is outside joint 4's limits).
// Solved: the solver reports success, FK of its answer reaches the target (telear at 1.5e-6 m /
// rad; KDL at its looser 1e-5 m, 1e-3 rad) and every joint is within its limits. Times: thread
// CPU time, one reading per solve, failures included.

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench/cpu_timing.hpp"
#include "bench/ik_timing.hpp"
#include "bench/kdl_chain.hpp"
#include "bench/kin_table.hpp"
#include "bench/kin_workload.hpp"
#include "telear/core/ik_numeric.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_description.hpp"

namespace {

using namespace telear;

struct Outcome {
  bool success;
  Eigen::VectorXd q;
};

}  // namespace

int main(int argc, char** argv) {
  const int poses = argc > 1 ? std::atoi(argv[1]) : 10000;
  if (poses < 100) {
    std::cerr << "redundant_ik_bench: poses must be at least 100\n";
    return 2;
  }
  const std::string robot = argc > 2 ? argv[2] : "arm7";
  auto description = core::load_robot_description({robot, "", {}});
  if (!description) {
    std::cerr << "redundant_ik_bench: " << description.error().message << "\n";
    return 2;
  }
  const core::RobotModel& model = *description->model;
  const std::optional<Eigen::VectorXd> ready_pose = model.named_configuration("ready");
  if (model.dof() <= 6 || !ready_pose) {
    std::cerr << "redundant_ik_bench: robot '" << robot
              << "' needs more than 6 joints and a named configuration 'ready'\n";
    return 2;
  }
  auto built = bench::kdl_chain_from_urdf(*description);
  if (!built) {
    std::cerr << "redundant_ik_bench: " << built.error().message << "\n";
    return 2;
  }
  const KDL::Chain chain = *built;
  const auto nj = chain.getNrOfJoints();
  std::printf("redundant_ik_bench: %s (%d joints), %d IK targets, %u hardware threads%s\n",
              model.name().c_str(), model.dof(), poses, std::thread::hardware_concurrency(),
#ifdef NDEBUG
              ""
#else
              " (assertions on: not a Release build)"
#endif
  );

  const std::vector<bench::IkCase> cases = bench::make_ik_cases(model, poses, 3);
  const Eigen::VectorXd& ready = *ready_pose;

  // The baseline is the same arm: KDL's tool frame equals telear's.
  core::KinematicsData data(model);
  KDL::ChainFkSolverPos_recursive kdl_fk(chain);
  KDL::Frame F;
  double fk_max_diff = 0.0;
  for (const auto& c : cases) {
    core::forward_kinematics(model, data, c.q_true);
    kdl_fk.JntToCart(bench::to_kdl(c.q_true), F);
    fk_max_diff =
        std::max(fk_max_diff,
                 (bench::from_kdl(F).matrix() - data.T_base_tool.matrix()).cwiseAbs().maxCoeff());
  }

  std::vector<bench::Row> rows;
  const std::vector<Eigen::VectorXd> qs = bench::random_configurations(model, 1024, 1);
  std::vector<KDL::JntArray> qs_kdl;
  for (const auto& q : qs) qs_kdl.push_back(bench::to_kdl(q));
  const double fk_telear = bench::best_ns_per_call([&](long i) {
    core::forward_kinematics(model, data, qs[static_cast<size_t>(i & 1023)]);
    bench::keep(data.T_base_tool);
  });
  std::vector<KDL::Frame> frames(chain.getNrOfSegments());
  const double fk_kdl = bench::best_ns_per_call([&](long i) {
    kdl_fk.JntToCart(qs_kdl[static_cast<size_t>(i & 1023)], frames);
    bench::keep(frames[0]);
  });
  rows.push_back({"FK, all frames (" + std::to_string(model.dof()) + " joints)", "ns", fk_telear,
                  fk_kdl, "", ""});

  core::NumericIkSolver solver(model);
  const KDL::JntArray ready_kdl = bench::to_kdl(ready);
  KDL::ChainIkSolverPos_LMA lma(chain);
  KDL::JntArray q_kdl(nj);
  std::vector<KDL::Frame> targets_kdl;
  for (const auto& c : cases) targets_kdl.push_back(bench::to_kdl(c.T_base_tool));

  const bench::IkStats lm = bench::time_numeric_ik(
      model, cases,
      [&](size_t k) {
        const core::NumericIkResult r = solver.solve(cases[k].T_base_tool, ready);
        return Outcome{r.success, r.q};
      },
      1.5e-6, 1.5e-6);
  const bench::IkStats nearest = bench::time_numeric_ik(
      model, cases,
      [&](size_t k) {
        auto r = core::solve_ik_nearest(model, cases[k].T_base_tool, ready);
        return r ? Outcome{true, r->q} : Outcome{false, ready};
      },
      1.5e-6, 1.5e-6);
  // What a Cartesian jog pays: the current pose near the answer (q_true + up to 0.1 rad).
  const bench::IkStats nearest_seeded = bench::time_numeric_ik(
      model, cases,
      [&](size_t k) {
        auto r = core::solve_ik_nearest(model, cases[k].T_base_tool, cases[k].q_near);
        return r ? Outcome{true, r->q} : Outcome{false, ready};
      },
      1.5e-6, 1.5e-6);
  const bench::IkStats kdl = bench::time_numeric_ik(
      model, cases,
      [&](size_t k) {
        const int rc = lma.CartToJnt(ready_kdl, targets_kdl[k], q_kdl);
        return Outcome{rc >= 0, q_kdl.data};
      },
      1e-5, 1e-3);

  auto add_ik = [&](const std::string& name, const bench::IkStats& t) {
    rows.push_back({name + ": solved", "%", t.solved_percent, kdl.solved_percent, ">= 99.9 %",
                    t.solved_percent >= 99.9 ? "yes" : "no"});
    rows.push_back({name + ": mean", "us", t.mean_us, kdl.mean_us, "<= 50 us, >= 10x KDL",
                    bench::join_met(bench::met_time(t.mean_us, 50.0, "us"),
                                    bench::met_ratio(kdl.mean_us / t.mean_us, 10.0))});
    rows.push_back({name + ": p99", "us", t.p99_us, kdl.p99_us, "", ""});
  };
  add_ik("IK, LM (NumericIkSolver)", lm);
  add_ik("IK, LM + null space (solve_ik_nearest)", nearest);
  std::vector<KDL::JntArray> seeds_kdl;
  for (const auto& c : cases) seeds_kdl.push_back(bench::to_kdl(c.q_near));
  const bench::IkStats kdl_seeded = bench::time_numeric_ik(
      model, cases,
      [&](size_t k) {
        const int rc = lma.CartToJnt(seeds_kdl[k], targets_kdl[k], q_kdl);
        return Outcome{rc >= 0, q_kdl.data};
      },
      1e-5, 1e-3);
  rows.push_back({"IK, LM + null space, seeded near: solved", "%", nearest_seeded.solved_percent,
                  kdl_seeded.solved_percent, "", ""});
  rows.push_back({"IK, LM + null space, seeded near: mean", "us", nearest_seeded.mean_us,
                  kdl_seeded.mean_us, "", ""});
  bench::print_table(rows, std::cout);
  std::printf(
      "\ncheck: KDL FK vs telear FK, tool pose of %d configurations: max |difference| %.2g\n",
      poses, fk_max_diff);
  std::printf(
      "note: KDL's LMA ignores joint limits: reported solved but outside them: %d "
      "(telear LM %d, with null space %d); failing the FK check: KDL %d, telear %d, %d\n",
      kdl.outside_limits, lm.outside_limits, nearest.outside_limits, kdl.unverified, lm.unverified,
      nearest.unverified);
  return 0;
}
