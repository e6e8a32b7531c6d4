// ExecutePlan over real gRPC on loopback: the server times the plan's waypoints itself and
// executes only when its hash is the client's (telear/net/plan_message.hpp); every refusal
// says why and leaves the arm where it was.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "robot_test_support.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/net/robot_messages.hpp"
#include "telear/net/robot_service.hpp"

namespace telear::net::test {
namespace {

using ::testing::HasSubstr;

// From the arm's current q0 through two via points and back to a stop near q0.
core::Trajectory via_plan(const Eigen::VectorXd& q0, const core::TrajectoryOptions& options = {}) {
  Eigen::VectorXd q1 = q0, q2 = q0, q3 = q0;
  q1[0] += 0.10;
  q1[1] += 0.05;
  q2[0] += 0.15;
  q2[2] -= 0.08;
  q3[2] -= 0.10;
  std::vector<core::JointWaypoint> w{
      {q0, 0.0, 1.0}, {q1, 0.0, std::nullopt, true}, {q2, 0.0, 0.5, true}, {q3}};
  auto trajectory = core::Trajectory::create(*telear::test::puma560(), std::move(w), options);
  EXPECT_TRUE(trajectory) << trajectory.error().message;
  return *trajectory;
}

v1::ExecutePlanRequest plan_request(const std::string& id, const core::Trajectory& trajectory,
                                    const v1::Lease& lease) {
  v1::ExecutePlanRequest request;
  request.set_lease_id(lease.lease_id());
  const Status filled = fill_plan_message(id, trajectory, *request.mutable_plan());
  EXPECT_TRUE(filled.ok()) << filled.error().message;
  return request;
}

TEST(RobotPlan, AMatchingPlanIsExecutedAsPreviewed) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  const core::Trajectory trajectory = via_plan(q_of(read_state(*stub)));
  const std::string hash = *core::plan_hash(trajectory);
  const v1::ExecutePlanRequest request = plan_request("plan-1", trajectory, lease);
  // The digest's 32 raw bytes on the wire, its hex in the API.
  EXPECT_EQ(request.plan().plan_hash().size(), 32u);
  EXPECT_EQ(plan_hash_hex(request.plan().plan_hash()), hash);
  EXPECT_EQ(request.plan().algorithm(), core::kTrajectoryAlgorithm);
  v1::ExecutePlanResponse response;
  const grpc::Status status = stub->ExecutePlan(context().get(), request, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(response.plan_id(), "plan-1");
  EXPECT_FALSE(response.duplicate());
  EXPECT_EQ(plan_hash_hex(response.plan_hash()), hash);
  EXPECT_EQ(response.algorithm(), core::kTrajectoryAlgorithm);
  // The server's trajectory is the client's, to the bit.
  EXPECT_EQ(response.duration_s(), trajectory.duration());

  const v1::RobotState done = stream_until(
      *stub, [](const v1::RobotState& s) { return s.last_trajectory_id() == "plan-1"; }, 10.0);
  EXPECT_EQ(done.last_trajectory_status(), v1::TRAJECTORY_STATUS_COMPLETED);
  EXPECT_LT((q_of(done) - trajectory.waypoints().back().q).cwiseAbs().maxCoeff(), 1e-3);

  // A retry after a lost reply: the first acceptance, with its hash, nothing new.
  v1::ExecutePlanResponse again;
  ASSERT_TRUE(stub->ExecutePlan(context().get(), request, &again).ok());
  EXPECT_TRUE(again.duplicate());
  EXPECT_EQ(plan_hash_hex(again.plan_hash()), hash);
  EXPECT_EQ(again.accepted_ns(), response.accepted_ns());
  EXPECT_EQ(read_state(*stub).mode(), v1::ROBOT_MODE_IDLE);
}

TEST(RobotPlan, RefusalsSayWhyAndNothingMoves) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  const v1::RobotState before = read_state(*stub);
  const Eigen::VectorXd q0 = q_of(before);
  const core::Trajectory trajectory = via_plan(q0);
  const std::string hash = *core::plan_hash(trajectory);

  struct Case {
    const char* name;
    v1::ExecutePlanRequest request;
    std::string reason;
  };
  std::vector<Case> cases;
  {
    auto r = plan_request("p-hash", trajectory, lease);
    std::string other = hash;
    other[0] = other[0] == '0' ? '1' : '0';
    r.mutable_plan()->set_plan_hash(*plan_hash_bytes(other));
    cases.push_back({"another hash", r,
                     "plan 'p-hash' rejected: its hash does not match: the client's is '" + other +
                         "', the server's is '" + hash + "' (" +
                         std::string(core::kTrajectoryAlgorithm) + ")"});
  }
  {
    // The hex digits instead of the digest: cut and its length said.
    auto r = plan_request("p-hex", trajectory, lease);
    r.mutable_plan()->set_plan_hash(hash);
    cases.push_back(
        {"hex digits sent", r,
         "its hash does not match: the client's is '" + plan_hash_hex(hash.substr(0, 32)) +
             "...' (64 bytes, not the 32 of a SHA-256 digest), the server's is '" + hash + "'"});
  }
  {
    auto r = plan_request("p-nohash", trajectory, lease);
    r.mutable_plan()->clear_plan_hash();
    cases.push_back({"no hash", r,
                     "plan 'p-nohash' rejected: its hash does not match: the client's is '' (0 "
                     "bytes, not the 32 of a SHA-256 digest), the server's is '" +
                         hash + "'"});
  }
  {
    // The waypoints changed after hashing by a nanoradian: the server's hash differs.
    auto r = plan_request("p-edit", trajectory, lease);
    r.mutable_plan()->mutable_waypoints(2)->set_q(0, r.plan().waypoints(2).q(0) + 1e-9);
    cases.push_back({"edited after hashing", r,
                     "its hash does not match: the client's is '" + hash + "', the server's is '"});
  }
  {
    auto r = plan_request("p-algo", trajectory, lease);
    r.mutable_plan()->set_algorithm("telear-blend-0");
    cases.push_back({"unknown algorithm", r,
                     "plan 'p-algo' rejected: unknown time parameterization 'telear-blend-0': "
                     "this server times plans with '" +
                         std::string(core::kTrajectoryAlgorithm) + "' only"});
  }
  {
    auto r = plan_request("p-nan", trajectory, lease);
    r.mutable_plan()->mutable_waypoints(1)->set_q(2, std::numeric_limits<double>::quiet_NaN());
    cases.push_back({"NaN", r,
                     "plan 'p-nan' rejected: waypoint[1]: joint 3 (elbow) value is not a finite "
                     "number: nan"});
  }
  {
    auto r = plan_request("p-size", trajectory, lease);
    r.mutable_plan()->mutable_waypoints(2)->add_q(0.0);
    cases.push_back({"wrong size", r, "waypoint[2]: expected 6 joint values, got 7"});
  }
  {
    auto r = plan_request("p-limit", trajectory, lease);
    r.mutable_plan()->mutable_waypoints(3)->set_q(1, 2.5);
    cases.push_back(
        {"beyond a limit", r, "waypoint[3]: joint 2 (shoulder) would be at 143.24 deg"});
  }
  {
    auto r = plan_request("p-scale", trajectory, lease);
    r.mutable_plan()->set_velocity_scale(0.0);
    cases.push_back({"no scale", r, "velocity_scale must be in [0.001, 1], got 0"});
  }
  {
    auto r = plan_request("p-long", trajectory, lease);
    r.mutable_plan()->mutable_waypoints(3)->set_min_duration_s(7200.0);
    cases.push_back({"too long a segment", r, "exceeds the maximum of 3600 s"});
  }
  {
    auto r = plan_request("p-many", trajectory, lease);
    while (r.plan().waypoints_size() <= 10000)
      *r.mutable_plan()->add_waypoints() = r.plan().waypoints(3);
    cases.push_back({"too many waypoints", r, "10001 waypoints, more than the maximum of 10000"});
  }
  {
    auto r = plan_request("p-none", trajectory, lease);
    r.mutable_plan()->clear_waypoints();
    cases.push_back({"no waypoints", r, "plan 'p-none' rejected: it has no waypoints"});
  }
  {
    auto r = plan_request(std::string(129, 'x'), trajectory, lease);
    cases.push_back({"id too long", r, "plan rejected: its id is 129 characters long"});
  }
  {
    Eigen::VectorXd off = q0;
    off[1] += 0.12;
    cases.push_back({"start far off", plan_request("p-start", via_plan(off), lease),
                     "starts 0.120 rad (6.88 deg) from the current state at joint 2 (shoulder)"});
  }
  for (Case& c : cases) {
    SCOPED_TRACE(c.name);
    v1::ExecutePlanResponse response;
    const grpc::Status status = stub->ExecutePlan(context().get(), c.request, &response);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_THAT(status.error_message(), HasSubstr(c.reason));
  }
  const v1::RobotState after = read_state(*stub);
  EXPECT_EQ(after.mode(), v1::ROBOT_MODE_IDLE);
  EXPECT_EQ(after.last_trajectory_id(), "");
  EXPECT_TRUE(q_of(after).isApprox(q0, 0.0)) << q_of(after).transpose();

  // Without the lease: refused before anything else.
  v1::ExecutePlanRequest no_lease = plan_request("p-lease", trajectory, lease);
  no_lease.set_lease_id("not-the-lease");
  v1::ExecutePlanResponse response;
  EXPECT_EQ(stub->ExecutePlan(context().get(), no_lease, &response).error_code(),
            grpc::StatusCode::PERMISSION_DENIED);
}

TEST(RobotPlan, TheHashTravelsAsTheDigestsBytes) {
  const std::string hex = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
  auto bytes = plan_hash_bytes(hex);
  ASSERT_TRUE(bytes) << bytes.error().message;
  ASSERT_EQ(bytes->size(), 32u);
  EXPECT_EQ(static_cast<unsigned char>((*bytes)[0]), 0xbau);
  EXPECT_EQ(static_cast<unsigned char>((*bytes)[31]), 0xadu);
  EXPECT_EQ(plan_hash_hex(*bytes), hex);
  EXPECT_EQ(plan_hash_bytes("abc").error().message,
            "a plan hash is 64 lowercase hex digits, got 3 characters");
  std::string upper = hex;
  upper[10] = 'F';
  EXPECT_EQ(plan_hash_bytes(upper).error().message,
            "a plan hash is lowercase hex digits; character 11 or 12 is not one");
}

TEST(RobotPlan, ThePlanMessageIsAFractionOfTheSamples) {
  const core::Trajectory trajectory = via_plan(Eigen::VectorXd::Constant(6, 0.3));
  v1::ExecutePlanRequest plan;
  ASSERT_TRUE(fill_plan_message("p1", trajectory, *plan.mutable_plan()).ok());
  v1::ExecuteTrajectoryRequest samples;
  fill_trajectory_request("p1", *trajectory.sampled(100.0), samples);
  EXPECT_LT(plan.ByteSizeLong() * 5, samples.ByteSizeLong());
}

}  // namespace
}  // namespace telear::net::test
