// PreviewPlan over real gRPC on loopback: the server times and checks a plan as ExecutePlan
// would (one function, RobotService::prepare_plan) and answers the hash a client that cannot
// time plans itself then sends with ExecutePlan; a plan ExecutePlan would refuse is refused
// in preview with the same status and message, and nothing moves either way.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "robot_test_support.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/robot_service.hpp"

namespace telear::net::test {
namespace {

using ::testing::HasSubstr;

RobotClientOptions preview_client_options(const RobotServer& server,
                                          const std::string& token = kToken) {
  RobotClientOptions options;
  options.address = server.address();
  options.token = token;
  options.client_name = "previewer";
  return options;
}

// From q0 through a via point to a stop, the gripper closing on arrival.
std::vector<core::JointWaypoint> via_waypoints(const Eigen::VectorXd& q0) {
  Eigen::VectorXd q1 = q0, q2 = q0;
  q1[0] += 0.10;
  q1[1] += 0.05;
  q2[0] += 0.15;
  q2[2] -= 0.08;
  return {{q0}, {q1, 0.0, std::nullopt, true}, {q2, 0.0, 0.2}};
}

core::TrajectoryOptions half_speed() {
  core::TrajectoryOptions options;
  options.velocity_scale = 0.5;
  options.acceleration_scale = 0.5;
  return options;
}

v1::PreviewPlanRequest preview_request(const std::string& id,
                                       const std::vector<core::JointWaypoint>& waypoints) {
  v1::PreviewPlanRequest request;
  fill_plan_waypoints(id, waypoints, half_speed(), *request.mutable_plan());
  return request;
}

TEST(RobotPlanPreview, TheServersHashIsTheInProcessOneAndExecutePlanRunsIt) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const Eigen::VectorXd q0 = q_of(read_state(*stub));
  const std::vector<core::JointWaypoint> waypoints = via_waypoints(q0);
  auto trajectory = core::Trajectory::create(*telear::test::puma560(), waypoints, half_speed());
  ASSERT_TRUE(trajectory) << trajectory.error().message;
  const std::string hash = *core::plan_hash(*trajectory);

  // An observer (no token, no lease) may preview.
  RobotClient observer(preview_client_options(*server, ""));
  auto preview = observer.preview_plan("preview-1", waypoints, half_speed(), true);
  ASSERT_TRUE(preview) << preview.error().message;
  EXPECT_EQ(preview->plan_id, "preview-1");
  EXPECT_EQ(preview->plan_hash, hash);
  EXPECT_EQ(preview->algorithm, core::kTrajectoryAlgorithm);
  EXPECT_EQ(preview->duration_s, trajectory->duration());  // to the bit
  EXPECT_FALSE(preview->samples_omitted);
  // The samples are those the driver would get: the trajectory at 100 Hz (times in whole ns).
  const core::TimedWaypoints expected = *trajectory->sampled(kPlanExecutionRateHz);
  ASSERT_EQ(preview->samples.q.size(), expected.q.size());
  for (size_t k = 0; k < expected.q.size(); ++k) {
    EXPECT_NEAR(preview->samples.times[k], expected.times[k], 1e-9) << k;
    EXPECT_EQ(preview->samples.q[k], expected.q[k]) << k;
  }
  ASSERT_EQ(preview->samples.gripper.size(), 1u);
  EXPECT_EQ(preview->samples.gripper[0].opening, 0.2);
  // Without an algorithm: the server's (a client that does not time plans need not know its
  // name); the answer names it for ExecutePlan.
  {
    v1::PreviewPlanRequest request = preview_request("preview-1", waypoints);
    request.mutable_plan()->clear_algorithm();
    v1::PreviewPlanResponse response;
    const grpc::Status status = stub->PreviewPlan(context("").get(), request, &response);
    ASSERT_TRUE(status.ok()) << status.error_message();
    EXPECT_EQ(response.algorithm(), core::kTrajectoryAlgorithm);
    EXPECT_EQ(plan_hash_hex(response.plan_hash()), hash);
    EXPECT_TRUE(response.samples().empty());
  }
  // Without samples: the hash and the duration only.
  auto bare = observer.preview_plan("preview-1", waypoints, half_speed());
  ASSERT_TRUE(bare) << bare.error().message;
  EXPECT_EQ(bare->plan_hash, hash);
  EXPECT_TRUE(bare->samples.q.empty());
  EXPECT_EQ(read_state(*stub).mode(), v1::ROBOT_MODE_IDLE);  // nothing moved

  // The lease holder sends the waypoints with the previewed hash: exactly that motion runs.
  RobotClient operator_client(preview_client_options(*server));
  ASSERT_TRUE(operator_client.acquire_lease().ok());
  auto ack = operator_client.execute_plan("preview-1", waypoints, half_speed(), preview->plan_hash);
  ASSERT_TRUE(ack) << ack.error().message;
  EXPECT_EQ(ack->plan_hash, hash);
  EXPECT_EQ(ack->duration_s, trajectory->duration());
  const v1::RobotState done = stream_until(
      *stub, [](const v1::RobotState& s) { return s.last_trajectory_id() == "preview-1"; }, 10.0);
  EXPECT_EQ(done.last_trajectory_status(), v1::TRAJECTORY_STATUS_COMPLETED);
  EXPECT_LT((q_of(done) - waypoints.back().q).cwiseAbs().maxCoeff(), 1e-3);

  // Its id is taken now: a preview says ExecutePlan would not run a new plan under it.
  auto again = observer.preview_plan("preview-1", via_waypoints(q_of(done)), half_speed());
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error().message,
            "preview plan: plan 'preview-1' rejected: its id was already "
            "accepted, so ExecutePlan would answer with that first acceptance and not run this "
            "plan; choose a new id");
  // A hash that is not 64 hex digits never leaves the client.
  auto bad_hash = operator_client.execute_plan("preview-2", waypoints, half_speed(), "abc");
  ASSERT_FALSE(bad_hash);
  EXPECT_EQ(bad_hash.error().message,
            "execute plan: a plan hash is 64 lowercase hex digits, got 3 characters");
}

TEST(RobotPlanPreview, APlanExecutePlanRefusesIsRefusedWithTheSameMessage) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  const Eigen::VectorXd q0 = q_of(read_state(*stub));
  const std::vector<core::JointWaypoint> good = via_waypoints(q0);

  struct Case {
    const char* name;
    v1::PreviewPlanRequest request;
    std::string reason;
    std::string hash;  // for ExecutePlan: the right one where the plan can be timed
  };
  std::vector<Case> cases;
  {
    auto r = preview_request("p-nan", good);
    r.mutable_plan()->mutable_waypoints(1)->set_q(2, std::numeric_limits<double>::quiet_NaN());
    cases.push_back({"NaN",
                     r,
                     "plan 'p-nan' rejected: waypoint[1]: joint 3 (elbow) value is not a finite "
                     "number: nan",
                     {}});
  }
  {
    auto r = preview_request("p-inf", good);
    r.mutable_plan()->mutable_waypoints(2)->set_min_duration_s(
        std::numeric_limits<double>::infinity());
    cases.push_back({"infinite duration", r, "plan 'p-inf' rejected: waypoint[2]", {}});
  }
  {
    auto r = preview_request("p-limit", good);
    r.mutable_plan()->mutable_waypoints(2)->set_q(1, 2.5);
    cases.push_back(
        {"beyond a limit", r, "waypoint[2]: joint 2 (shoulder) would be at 143.24 deg", {}});
  }
  {
    auto r = preview_request("p-algo", good);
    r.mutable_plan()->set_algorithm("telear-blend-0");
    cases.push_back({"unknown algorithm",
                     r,
                     "plan 'p-algo' rejected: unknown time parameterization 'telear-blend-0'",
                     {}});
  }
  {
    auto r = preview_request("p-none", good);
    r.mutable_plan()->clear_waypoints();
    cases.push_back({"no waypoints", r, "plan 'p-none' rejected: it has no waypoints", {}});
  }
  {
    auto r = preview_request("", good);
    cases.push_back({"no id", r, "plan rejected: its id is empty", {}});
  }
  {
    Eigen::VectorXd off = q0;
    off[1] += 0.12;
    // Timed and hashed fine: ExecutePlan refuses it after the hash, at the start state.
    auto timed =
        core::Trajectory::create(*telear::test::puma560(), via_waypoints(off), half_speed());
    ASSERT_TRUE(timed) << timed.error().message;
    cases.push_back({"start far off", preview_request("p-start", via_waypoints(off)),
                     "starts 0.120 rad (6.88 deg) from the current state at joint 2 (shoulder)",
                     *plan_hash_bytes(*core::plan_hash(*timed))});
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    v1::PreviewPlanResponse preview;
    const grpc::Status previewed = stub->PreviewPlan(context().get(), c.request, &preview);
    EXPECT_EQ(previewed.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_THAT(previewed.error_message(), HasSubstr(c.reason));
    // ExecutePlan: refused in the same words (before the hash is compared, or after it with
    // the right hash).
    v1::ExecutePlanRequest execute;
    execute.set_lease_id(lease.lease_id());
    *execute.mutable_plan() = c.request.plan();
    execute.mutable_plan()->set_plan_hash(c.hash.empty() ? std::string(32, '\0') : c.hash);
    v1::ExecutePlanResponse response;
    const grpc::Status executed = stub->ExecutePlan(context().get(), execute, &response);
    EXPECT_EQ(executed.error_code(), previewed.error_code());
    EXPECT_EQ(executed.error_message(), previewed.error_message());
  }

  // The arm e-stopped: FAILED_PRECONDITION in both.
  v1::EStopResponse stopped;
  ASSERT_TRUE(stub->EStop(context().get(), v1::EStopRequest(), &stopped).ok());
  const v1::PreviewPlanRequest request = preview_request("p-estop", good);
  v1::PreviewPlanResponse preview;
  const grpc::Status previewed = stub->PreviewPlan(context().get(), request, &preview);
  EXPECT_EQ(previewed.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_THAT(previewed.error_message(),
              HasSubstr("trajectory 'p-estop' rejected: the e-stop is engaged"));

  const v1::RobotState after = read_state(*stub);
  EXPECT_EQ(after.last_trajectory_id(), "");
  EXPECT_TRUE(q_of(after).isApprox(q0, 0.0)) << q_of(after).transpose();
}

TEST(RobotPlanPreview, ALongPlanIsPreviewedWithoutItsSamples) {
  auto server = start_server();
  auto stub = stub_for(*server);
  std::vector<core::JointWaypoint> waypoints = via_waypoints(q_of(read_state(*stub)));
  waypoints.back().min_duration = 400.0;  // 40,000 samples at 100 Hz, over kMaxPreviewSamples
  RobotClient observer(preview_client_options(*server, ""));
  auto preview = observer.preview_plan("long", waypoints, half_speed(), true);
  ASSERT_TRUE(preview) << preview.error().message;
  EXPECT_TRUE(preview->samples_omitted);
  EXPECT_TRUE(preview->samples.q.empty());
  EXPECT_GE(preview->duration_s, 400.0);
  auto trajectory = core::Trajectory::create(*telear::test::puma560(), waypoints, half_speed());
  ASSERT_TRUE(trajectory) << trajectory.error().message;
  EXPECT_EQ(preview->plan_hash, *core::plan_hash(*trajectory));
}

TEST(RobotPlanPreview, NeedsTheTokenWhenTheServerAllowsNoObservers) {
  RobotServerOptions options = server_options();
  options.allow_observers = false;
  auto server = start_server(std::move(options));
  auto stub = stub_for(*server);
  Eigen::VectorXd q0(6);
  q0 << 0.0, 0.5, -0.5, 0.0, 0.5, 0.0;  // start_server's (the state needs the token here)
  const v1::PreviewPlanRequest request = preview_request("p-auth", via_waypoints(q0));
  v1::PreviewPlanResponse response;
  EXPECT_EQ(stub->PreviewPlan(context("").get(), request, &response).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(stub->PreviewPlan(context("wrong").get(), request, &response).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
  // With the token and without the lease: previewing moves nothing, so no lease is needed.
  const grpc::Status status = stub->PreviewPlan(context().get(), request, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(response.plan_hash().size(), 32u);
}

}  // namespace
}  // namespace telear::net::test
