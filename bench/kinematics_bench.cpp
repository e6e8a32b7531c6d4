// Google Benchmark programs of telear's kinematics against Orocos KDL on the same chain
// (docs/benchmarks.md). `telear bench kin` times the same work and prints the ratio table;
// this program is for profiling one operation at a time, e.g.
//   build/bench/kinematics_bench --benchmark_filter=FK
// Every benchmark cycles through a fixed set of seeded random inputs, so branch predictors
// and caches see realistic, varying data rather than one repeated configuration.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/jacobian.hpp>
#include <vector>

#include "bench/kdl_chain.hpp"
#include "bench/kin_workload.hpp"
#include "telear/core/ik_analytic.hpp"
#include "telear/core/ik_numeric.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"

namespace telear::bench {
namespace {

constexpr int kInputs = 1024;  // power of two: the index wraps with a mask
constexpr int kIkCases = 1000;

struct Fixture {
  core::RobotModelPtr model;
  core::PumaGeometry geometry;
  KDL::Chain chain;
  std::vector<Eigen::VectorXd> q;
  std::vector<KDL::JntArray> q_kdl;
  std::vector<IkCase> ik;
  std::vector<KDL::Frame> ik_target_kdl;

  static const Fixture& get() {
    static const Fixture f = make();
    return f;
  }

 private:
  static Fixture make() {
    Fixture f;
    auto model = core::load_robot("puma560");
    if (!model) {
      std::fprintf(stderr, "kinematics_bench: %s\n", model.error().message.c_str());
      std::exit(2);
    }
    f.model = *model;
    auto geometry = core::puma_geometry(*f.model);
    if (!geometry) {
      std::fprintf(stderr, "kinematics_bench: %s\n", geometry.error().message.c_str());
      std::exit(2);
    }
    f.geometry = *geometry;
    auto chain = kdl_chain_from_dh(*f.model);
    if (!chain) {
      std::fprintf(stderr, "kinematics_bench: %s\n", chain.error().message.c_str());
      std::exit(2);
    }
    f.chain = *chain;
    f.q = random_configurations(*f.model, kInputs, 1);
    for (const auto& q : f.q) f.q_kdl.push_back(to_kdl(q));
    f.ik = make_ik_cases(*f.model, kIkCases, 2);
    for (const auto& c : f.ik) f.ik_target_kdl.push_back(to_kdl(c.T_base_tool));
    return f;
  }
};

// ---- telear ------------------------------------------------------------------------------

void BM_Telear_FK_AllFrames(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  core::KinematicsData data(*f.model);
  int k = 0;
  for (auto _ : state) {
    core::forward_kinematics(*f.model, data, f.q[static_cast<size_t>(k++ & (kInputs - 1))]);
    benchmark::DoNotOptimize(data.T_base_tool);
  }
}
BENCHMARK(BM_Telear_FK_AllFrames);

// One wrist joint (joint 5) changes: frames 5, 6 and the tool are recomputed.
void BM_Telear_FK_IncrementalWrist(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  core::KinematicsData data(*f.model);
  core::forward_kinematics(*f.model, data, f.q[0]);
  int k = 0;
  for (auto _ : state) {
    core::set_joint(*f.model, data, 4, f.q[static_cast<size_t>(k++ & (kInputs - 1))][4]);
    benchmark::DoNotOptimize(data.T_base_tool);
  }
}
BENCHMARK(BM_Telear_FK_IncrementalWrist);

// Full FK followed by the Jacobian: the work KDL's JntToJac does.
void BM_Telear_Jacobian_WithFK(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  core::KinematicsData data(*f.model);
  core::Jacobian J(6, f.model->dof());
  int k = 0;
  for (auto _ : state) {
    core::forward_kinematics(*f.model, data, f.q[static_cast<size_t>(k++ & (kInputs - 1))]);
    core::geometric_jacobian(*f.model, data, core::JacobianFrame::kBase, J);
    benchmark::DoNotOptimize(J.data());
  }
}
BENCHMARK(BM_Telear_Jacobian_WithFK);

// The Jacobian alone, from frames already computed (as inside an IK iteration).
void BM_Telear_Jacobian_FromFrames(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  core::KinematicsData data(*f.model);
  core::forward_kinematics(*f.model, data, f.q[0]);
  core::Jacobian J(6, f.model->dof());
  for (auto _ : state) {
    core::geometric_jacobian(*f.model, data, core::JacobianFrame::kBase, J);
    benchmark::DoNotOptimize(J.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_Telear_Jacobian_FromFrames);

// All 8 closed-form solutions, allocation-free core.
void BM_Telear_AnalyticIK_All8(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  core::PumaIkSolutions solutions;
  size_t k = 0;
  for (auto _ : state) {
    core::solve_puma_ik(f.geometry, f.ik[k++ % f.ik.size()].T_base_tool, solutions);
    benchmark::DoNotOptimize(solutions.q.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_Telear_AnalyticIK_All8);

// The same through the labelled API (configuration strings, vectors).
void BM_Telear_AnalyticIK_LabelledApi(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  size_t k = 0;
  for (auto _ : state) {
    core::AnalyticIkResult r =
        core::solve_analytic_ik(*f.model, f.geometry, f.ik[k++ % f.ik.size()].T_base_tool);
    benchmark::DoNotOptimize(r.solutions.data());
  }
}
BENCHMARK(BM_Telear_AnalyticIK_LabelledApi);

// telear's Levenberg-Marquardt; arg 0: cold start from q = 0, 1: seeded near the answer.
void BM_Telear_NumericIK(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  core::NumericIkSolver solver(*f.model);
  const bool seeded = state.range(0) == 1;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(f.model->dof());
  size_t k = 0;
  double solved = 0;
  for (auto _ : state) {
    const IkCase& c = f.ik[k++ % f.ik.size()];
    const core::NumericIkResult r = solver.solve(c.T_base_tool, seeded ? c.q_near : zero);
    solved += r.success ? 1 : 0;
    benchmark::DoNotOptimize(r.q.data());
  }
  state.counters["solved"] = benchmark::Counter(solved, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_Telear_NumericIK)->Arg(0)->Arg(1)->ArgName("seeded")->Unit(benchmark::kMicrosecond);

// ---- KDL ---------------------------------------------------------------------------------

void BM_KDL_FK_Tip(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  KDL::ChainFkSolverPos_recursive fk(f.chain);
  KDL::Frame T;
  int k = 0;
  for (auto _ : state) {
    fk.JntToCart(f.q_kdl[static_cast<size_t>(k++ & (kInputs - 1))], T);
    benchmark::DoNotOptimize(T);
  }
}
BENCHMARK(BM_KDL_FK_Tip);

void BM_KDL_FK_AllFrames(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  KDL::ChainFkSolverPos_recursive fk(f.chain);
  std::vector<KDL::Frame> frames(f.chain.getNrOfSegments());
  int k = 0;
  for (auto _ : state) {
    fk.JntToCart(f.q_kdl[static_cast<size_t>(k++ & (kInputs - 1))], frames);
    benchmark::DoNotOptimize(frames.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_KDL_FK_AllFrames);

void BM_KDL_Jacobian(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  KDL::ChainJntToJacSolver solver(f.chain);
  KDL::Jacobian J(f.chain.getNrOfJoints());
  int k = 0;
  for (auto _ : state) {
    solver.JntToJac(f.q_kdl[static_cast<size_t>(k++ & (kInputs - 1))], J);
    benchmark::DoNotOptimize(J.data.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_KDL_Jacobian);

// KDL's Levenberg-Marquardt position IK; arg 0: cold start from q = 0, 1: seeded near the
// answer. Counter "solved" is the fraction of calls that converged.
void BM_KDL_IK_LMA(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  KDL::ChainIkSolverPos_LMA solver(f.chain);
  const bool seeded = state.range(0) == 1;
  const KDL::JntArray zero(f.chain.getNrOfJoints());
  KDL::JntArray q_out(f.chain.getNrOfJoints());
  std::vector<KDL::JntArray> seeds;
  for (const auto& c : f.ik) seeds.push_back(to_kdl(c.q_near));
  size_t k = 0;
  double solved = 0;
  for (auto _ : state) {
    const size_t i = k++ % f.ik.size();
    const int rc = solver.CartToJnt(seeded ? seeds[i] : zero, f.ik_target_kdl[i], q_out);
    solved += rc >= 0 ? 1 : 0;
    benchmark::DoNotOptimize(q_out.data.data());
  }
  state.counters["solved"] = benchmark::Counter(solved, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_KDL_IK_LMA)->Arg(0)->Arg(1)->ArgName("seeded")->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace telear::bench

BENCHMARK_MAIN();
