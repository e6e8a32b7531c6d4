// Cartesian segments in ExecutePlan over real gRPC on loopback: only the operator's waypoints
// travel (with the cartesian flag), the server expands the line with the client's code and
// gets the client's hash; a line the arm cannot follow is refused (INVALID_ARGUMENT, where and
// why) and nothing moves.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "robot_test_support.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/net/robot_service.hpp"

namespace telear::net::test {
namespace {

using ::testing::HasSubstr;

core::JointWaypoint cartesian(Eigen::VectorXd q) {
  core::JointWaypoint w(std::move(q));
  w.cartesian = true;
  return w;
}

// The IK solution nearest q of q's tool pose moved by `offset` (base frame).
Eigen::VectorXd moved(const Eigen::VectorXd& q, const Eigen::Vector3d& offset) {
  const core::RobotModelPtr puma = telear::test::puma560();
  Eigen::Isometry3d T = core::tool_pose(*puma, q);
  T.translation() += offset;
  auto ik = core::solve_ik_nearest(*puma, T, q);
  EXPECT_TRUE(ik) << ik.error().message;
  return ik ? ik->q : q;
}

TEST(RobotCartesianPlan, TheServerExpandsTheLineAndGetsTheClientsHash) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  const Eigen::VectorXd q0 = q_of(read_state(*stub));
  const Eigen::VectorXd q1 = moved(q0, {0.06, 0.04, -0.05});
  // Out along a line, back along the same line.
  auto trajectory =
      core::Trajectory::create(*telear::test::puma560(), {{q0}, cartesian(q1), cartesian(q0)});
  ASSERT_TRUE(trajectory) << trajectory.error().message;
  ASSERT_GT(trajectory->waypoints().size(), 20u);  // expanded
  const std::string hash = *core::plan_hash(*trajectory);

  v1::ExecutePlanRequest request;
  request.set_lease_id(lease.lease_id());
  ASSERT_TRUE(fill_plan_message("line-1", *trajectory, *request.mutable_plan()).ok());
  // The operator's three waypoints only, the flag on the Cartesian ones.
  ASSERT_EQ(request.plan().waypoints_size(), 3);
  EXPECT_FALSE(request.plan().waypoints(0).cartesian());
  EXPECT_TRUE(request.plan().waypoints(1).cartesian());
  EXPECT_TRUE(request.plan().waypoints(2).cartesian());
  EXPECT_EQ(request.plan().algorithm(), core::kTrajectoryAlgorithm);

  v1::ExecutePlanResponse response;
  const grpc::Status status = stub->ExecutePlan(context().get(), request, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(plan_hash_hex(response.plan_hash()), hash);
  EXPECT_EQ(response.duration_s(), trajectory->duration());  // to the bit

  const v1::RobotState done = stream_until(
      *stub, [](const v1::RobotState& s) { return s.last_trajectory_id() == "line-1"; }, 10.0);
  EXPECT_EQ(done.last_trajectory_status(), v1::TRAJECTORY_STATUS_COMPLETED);
  EXPECT_LT((q_of(done) - q0).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(RobotCartesianPlan, ALineTheArmCannotFollowIsRefusedAndNothingMoves) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  const v1::RobotState before = read_state(*stub);
  const Eigen::VectorXd q0 = q_of(before);
  // To the mirror image of the tool's position through the base axis: the line crosses the
  // axis, where the PUMA's wrist cannot go (its shoulder offset).
  const core::RobotModelPtr puma = telear::test::puma560();
  Eigen::Isometry3d T = core::tool_pose(*puma, q0);
  T.translation().head<2>() = -T.translation().head<2>();
  auto far = core::solve_ik_nearest(*puma, T, q0);
  ASSERT_TRUE(far) << far.error().message;
  // The client cannot time it either; the message is built by hand, as a client that does
  // not run telear's parameterization would.
  ASSERT_FALSE(core::Trajectory::create(*puma, {{q0}, cartesian(far->q)}));
  v1::ExecutePlanRequest request;
  request.set_lease_id(lease.lease_id());
  v1::PlanMessage& plan = *request.mutable_plan();
  plan.set_plan_id("line-axis");
  plan.set_algorithm(std::string(core::kTrajectoryAlgorithm));
  plan.set_velocity_scale(1.0);
  plan.set_acceleration_scale(1.0);
  plan.add_waypoints()->mutable_q()->Add(q0.data(), q0.data() + 6);
  v1::PlanWaypoint* w = plan.add_waypoints();
  w->mutable_q()->Add(far->q.data(), far->q.data() + 6);
  w->set_cartesian(true);
  plan.set_plan_hash(std::string(32, '\0'));

  v1::ExecutePlanResponse response;
  const grpc::Status status = stub->ExecutePlan(context().get(), request, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(),
              HasSubstr("plan 'line-axis' rejected: waypoint[1]: the Cartesian segment from "
                        "waypoint[0] cannot be followed at "));
  EXPECT_THAT(status.error_message(), HasSubstr("the arm cannot reach the line there"));
  const v1::RobotState after = read_state(*stub);
  EXPECT_EQ(after.mode(), v1::ROBOT_MODE_IDLE);
  EXPECT_EQ(after.last_trajectory_id(), "");
  EXPECT_TRUE(q_of(after).isApprox(q0, 0.0)) << q_of(after).transpose();
}

}  // namespace
}  // namespace telear::net::test
