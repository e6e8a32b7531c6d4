// The robot server as the collision authority (telear/net/motion_collision_guard.hpp), over
// real gRPC on loopback: the simulated PUMA 560 (primitive collision shapes) in its shipped
// workspace (data/workspaces/puma560_table.yaml). Trajectories and plans through the table are
// refused with the contact named and nothing moves; jogs toward it stop before the margin.
// The shipped 7-joint arm in its workspace (data/workspaces/arm7_table.yaml: a tray and the box
// on it): the fingers closing on the box are no contact, the box carried through the tray is.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <limits>
#include <optional>
#include <thread>
#include <vector>

#include "robot_test_support.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/net/robot_client.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::net::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const core::RobotDescription& puma() {
  static const core::RobotDescription description = [] {
    auto d = core::load_robot_description({"puma560", "", {}});
    EXPECT_TRUE(d) << d.error().message;
    return *d;
  }();
  return description;
}

std::string table_file() {
  return core::default_workspace_file("puma560");
}

Result<std::unique_ptr<RobotServer>> create_server(const std::string& workspace_file,
                                                   const Eigen::VectorXd& initial_q) {
  RobotServerOptions options = server_options();
  options.robot_description = puma();
  options.workspace_file = workspace_file;
  sim::SimRobotDriverOptions driver_options;
  driver_options.robot.initial_q = initial_q;
  auto driver = sim::SimRobotDriver::create(puma().model, driver_options);
  EXPECT_TRUE(driver) << driver.error().message;
  return RobotServer::create(std::move(driver).value(), std::move(options));
}

// Over the table (top face at z = 0.40 m), away from the box on it, elbow up (the PUMA's
// IK, within the limits): the wrist centre at (0.515, -0.658, 0.624) m, the hand tilted 23 deg
// from straight down; the same shifted by 0.1 rad of waist; and the wrist centre at
// (0.45, -0.60, 0.30) m, through the top, hand pointing down.
Eigen::VectorXd above_table() {
  Eigen::VectorXd q(6);
  q << -0.7259, 0.25, -2.1387, 0.0, -0.842, 0.0;
  return q;
}
Eigen::VectorXd above_table_shifted() {
  Eigen::VectorXd q = above_table();
  q[0] += 0.1;
  return q;
}
Eigen::VectorXd through_table() {
  Eigen::VectorXd q(6);
  q << -0.7259, -0.1608, -2.1387, 0.0, -0.842, 0.0;
  return q;
}

v1::ExecuteTrajectoryRequest request_through(const std::string& id, const Eigen::VectorXd& q0,
                                             const Eigen::VectorXd& q1, const v1::Lease& lease) {
  auto trajectory = core::Trajectory::create(*puma().model, {{q0}, {q1}});
  EXPECT_TRUE(trajectory) << trajectory.error().message;
  auto sampled = trajectory->sampled(50.0);
  EXPECT_TRUE(sampled) << sampled.error().message;
  v1::ExecuteTrajectoryRequest request;
  request.set_trajectory_id(id);
  request.set_lease_id(lease.lease_id());
  for (size_t k = 0; k < sampled->times.size(); ++k) {
    v1::Waypoint* w = request.add_waypoints();
    w->set_time_from_start_ns(static_cast<std::int64_t>(std::llround(sampled->times[k] * 1e9)));
    w->mutable_q()->Assign(sampled->q[k].data(), sampled->q[k].data() + sampled->q[k].size());
  }
  return request;
}

// Runs a free trajectory to `q` and waits until the arm rests there.
void move_to(v1::RobotService::Stub& stub, const v1::Lease& lease, const Eigen::VectorXd& q,
             const std::string& id) {
  const v1::ExecuteTrajectoryRequest request =
      request_through(id, q_of(read_state(stub)), q, lease);
  v1::ExecuteTrajectoryResponse response;
  const grpc::Status status = stub.ExecuteTrajectory(context().get(), request, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  const v1::RobotState rest = stream_until(
      stub,
      [](const v1::RobotState& s) {
        return s.mode() == v1::ROBOT_MODE_IDLE && s.trajectory_id().empty();
      },
      10.0);
  ASSERT_TRUE((q_of(rest) - q).cwiseAbs().maxCoeff() < 1e-3) << q_of(rest).transpose();
}

// The smallest distance of any robot body to any workspace object at q.
double workspace_clearance(const Eigen::VectorXd& q, double gripper) {
  auto workspace = geometry::load_workspace(table_file());
  EXPECT_TRUE(workspace) << workspace.error().message;
  auto checker = geometry::make_collision_checker(puma(), *workspace);
  EXPECT_TRUE(checker) << checker.error().message;
  checker->set_configuration(q, gripper);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& pair : checker->pairs()) {
    if (pair.other_object >= 0) best = std::min(best, checker->distance(pair).distance_m);
  }
  return best;
}

TEST(RobotCollisionAuthority, ATrajectoryThroughTheTableIsRefusedAndNothingMoves) {
  auto server = create_server(table_file(), above_table());
  ASSERT_TRUE(server) << server.error().message;
  auto stub = stub_for(**server);
  const v1::Lease lease = acquire(*stub);
  const Eigen::VectorXd above = above_table_shifted();
  move_to(*stub, lease, above, "free");  // a free trajectory still executes

  const Eigen::VectorXd below = through_table();
  const v1::ExecuteTrajectoryRequest request = request_through("into-table", above, below, lease);
  v1::ExecuteTrajectoryResponse response;
  const grpc::Status status = stub->ExecuteTrajectory(context().get(), request, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("trajectory 'into-table' rejected: "
                                                "trajectory collides: at t="));
  EXPECT_THAT(status.error_message(), HasSubstr("touches 'table_top' (depth "));
  EXPECT_THAT(status.error_message(), HasSubstr(" link '"));

  // Nothing moved, and nothing starts later.
  const Eigen::VectorXd before = q_of(read_state(*stub));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const v1::RobotState after = read_state(*stub);
  EXPECT_EQ(after.mode(), v1::ROBOT_MODE_IDLE);
  EXPECT_LT((q_of(after) - before).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((q_of(after) - above).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(RobotCollisionAuthority, APlanThroughTheTableIsRefused) {
  auto server = create_server(table_file(), above_table());
  ASSERT_TRUE(server) << server.error().message;
  auto stub = stub_for(**server);
  const v1::Lease lease = acquire(*stub);
  const Eigen::VectorXd above = above_table();
  const Eigen::VectorXd below = through_table();

  auto trajectory = core::Trajectory::create(*puma().model, {{above}, {below}, {above}});
  ASSERT_TRUE(trajectory) << trajectory.error().message;
  v1::ExecutePlanRequest request;
  request.set_lease_id(lease.lease_id());
  ASSERT_TRUE(fill_plan_message("plan-into-table", *trajectory, *request.mutable_plan()).ok());
  v1::ExecutePlanResponse response;
  const grpc::Status status = stub->ExecutePlan(context().get(), request, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("trajectory 'plan-into-table' rejected: "
                                                "trajectory collides: at t="));
  EXPECT_THAT(status.error_message(), HasSubstr("'table_top'"));
  // PreviewPlan refuses it in the same words: the same check, the collision guard included.
  v1::PreviewPlanRequest preview;
  *preview.mutable_plan() = request.plan();
  v1::PreviewPlanResponse previewed;
  const grpc::Status preview_status = stub->PreviewPlan(context().get(), preview, &previewed);
  EXPECT_EQ(preview_status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(preview_status.error_message(), status.error_message());
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_LT((q_of(read_state(*stub)) - above).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(RobotCollisionAuthority, JogsTowardTheTableStopBeforeTheMargin) {
  auto server = create_server(table_file(), above_table());
  ASSERT_TRUE(server) << server.error().message;
  auto stub = stub_for(**server);
  const v1::Lease lease = acquire(*stub);

  // 1 cm steps straight down, each to rest, until the server refuses one.
  grpc::Status refusal;
  int accepted = 0;
  for (int step = 0; step < 60; ++step) {
    v1::JogRequest jog;
    jog.set_lease_id(lease.lease_id());
    jog.set_expires_ns(core::monotonic_ns() + 3'000'000'000);
    auto* increment = jog.mutable_cartesian_increment();
    increment->set_frame(v1::MOTION_FRAME_BASE);
    for (double v : {0.0, 0.0, -0.01}) increment->add_translation_m(v);
    for (int i = 0; i < 3; ++i) increment->add_rotation_rad(0.0);
    v1::JogResponse response;
    const grpc::Status status = stub->Jog(context().get(), jog, &response);
    if (!status.ok()) {
      refusal = status;
      break;
    }
    ++accepted;
    stream_until(*stub, [](const v1::RobotState& s) { return s.mode() == v1::ROBOT_MODE_IDLE; });
  }
  EXPECT_GT(accepted, 3);  // it did move down before stopping
  EXPECT_EQ(refusal.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(refusal.error_message(), HasSubstr("jog refused: link '"));
  EXPECT_THAT(refusal.error_message(), HasSubstr("'table_top', inside the safety margin 30.0 mm"));

  const v1::RobotState rest = read_state(*stub);
  const double clearance = workspace_clearance(q_of(rest), rest.gripper_opening());
  EXPECT_GE(clearance, kDefaultSafetyMarginM - 1e-3);
  EXPECT_LT(clearance, kDefaultSafetyMarginM + 0.011);  // within one step of it
}

TEST(RobotCollisionAuthority, AVelocityJogIntoTheTableIsRefused) {
  auto server = create_server(table_file(), above_table());
  ASSERT_TRUE(server) << server.error().message;
  auto stub = stub_for(**server);
  const v1::Lease lease = acquire(*stub);
  // The shoulder down at 0.3 rad/s for 2 s: the line to where it would be then crosses the
  // table top (through_table() is 0.41 rad of shoulder below).
  v1::JogRequest jog;
  jog.set_lease_id(lease.lease_id());
  jog.set_expires_ns(core::monotonic_ns() + 2'000'000'000);
  for (double v : {0.0, -0.3, 0.0, 0.0, 0.0, 0.0}) jog.mutable_joint_velocity()->add_qd(v);
  v1::JogResponse response;
  const grpc::Status status = stub->Jog(context().get(), jog, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("'table_top'"));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_LT((q_of(read_state(*stub)) - above_table()).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(RobotCollisionAuthority, GetInfoReturnsTheWorkspace) {
  auto server = create_server(table_file(), above_table());
  ASSERT_TRUE(server) << server.error().message;
  auto stub = stub_for(**server);
  v1::RobotInfo info;
  ASSERT_TRUE(stub->GetInfo(context().get(), v1::GetInfoRequest(), &info).ok());
  std::ifstream in(table_file());
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(info.collision_checked());
  EXPECT_EQ(info.workspace_yaml(), text);
  EXPECT_DOUBLE_EQ(info.safety_margin_m(), kDefaultSafetyMarginM);

  // A server without the description checks nothing and says so.
  auto plain = start_server();
  ASSERT_TRUE(plain);
  v1::RobotInfo plain_info;
  ASSERT_TRUE(stub_for(*plain)->GetInfo(context().get(), v1::GetInfoRequest(), &plain_info).ok());
  EXPECT_FALSE(plain_info.collision_checked());
  EXPECT_TRUE(plain_info.workspace_yaml().empty());
}

TEST(RobotCollisionAuthority, AMalformedWorkspaceFailsServerCreation) {
  test_files::TempDir tmp("collision_authority");
  const std::string path =
      tmp.write("bad_workspace.yaml",
                "name: bad\nobjects:\n  - name: plate\n    shape: box\n    size: [0.1, 0.1]\n");
  auto server = create_server(path, above_table());
  ASSERT_FALSE(server);
  EXPECT_THAT(server.error().message, HasSubstr("robot server: "));
  EXPECT_THAT(server.error().message, HasSubstr("plate"));
  EXPECT_THAT(server.error().message, HasSubstr("size"));

  RobotServerOptions no_description = server_options();
  no_description.workspace_file = table_file();
  EXPECT_THAT(no_description.validate().error().message,
              HasSubstr("needs the robot's description"));
}

// The shipped 7-joint arm (URDF with meshes) and a pick-and-place in its workspace, as the
// demo does it: the tool pointing down at the box on the tray (the grip centre is the tool
// centre point), closed on it at the grasp, carried 0.15 m along y and put down on the tray.
const core::RobotDescription& arm7() {
  static const core::RobotDescription description = [] {
    auto d = core::load_robot_description({"arm7", "", {}});
    EXPECT_TRUE(d) << d.error().message;
    return *d;
  }();
  return description;
}

Eigen::VectorXd arm7_ready() {
  const auto ready = arm7().model->named_configuration("ready");
  EXPECT_TRUE(ready.has_value());
  return ready ? *ready : Eigen::VectorXd::Zero(arm7().model->dof());
}

const Eigen::Vector3d kBox(0.5, -0.3, 0.045);  // its centre; 50 mm cube on the tray (top z = 0.02)
const Eigen::Vector3d kPlace(0.5, -0.15, 0.045);
const Eigen::Vector3d kUp(0.0, 0.0, 0.12);

struct TaskPose {
  Eigen::Vector3d grip;
  std::optional<double> gripper;  // commanded on arrival
};

// The joint waypoints through `poses` (IK from the previous one), from the ready pose.
std::vector<core::JointWaypoint> pick_and_place(const std::vector<TaskPose>& poses) {
  const core::RobotModel& model = *arm7().model;
  Eigen::Matrix3d down;
  down.col(0) = Eigen::Vector3d::UnitX();
  down.col(1) = -Eigen::Vector3d::UnitY();
  down.col(2) = -Eigen::Vector3d::UnitZ();
  std::vector<core::JointWaypoint> waypoints{{arm7_ready()}};
  for (const TaskPose& pose : poses) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = down;
    T.translation() = pose.grip;
    auto ik = core::solve_ik_nearest(model, T, waypoints.back().q);
    EXPECT_TRUE(ik) << pose.grip.transpose() << ": " << ik.error().message;
    if (!ik) return {};
    waypoints.emplace_back(ik->q, pose.gripper ? 1.2 : 0.0, pose.gripper);
  }
  return waypoints;
}

std::vector<TaskPose> demo_like_task(double carry_z) {
  return {{kBox + kUp, 1.0},
          {kBox, 0.0},  // the fingers close on the box
          {kBox + kUp, std::nullopt},
          {Eigen::Vector3d(kPlace.x(), kPlace.y(), carry_z), std::nullopt},
          {kPlace, 1.0},  // put down: the fingers open
          {kPlace + kUp, std::nullopt}};
}

Result<std::unique_ptr<RobotServer>> create_arm7_server() {
  RobotServerOptions options = server_options();
  // Leases of up to two minutes without a heartbeat: a test that runs the whole pick-and-place
  // sends none, and a loaded sanitizer build takes many seconds over it.
  options.lease.max_heartbeat_ns = 120'000'000'000;
  options.robot_description = arm7();
  options.workspace_file = core::default_workspace_file("arm7");
  sim::SimRobotDriverOptions driver_options;
  driver_options.robot.initial_q = arm7_ready();
  auto driver = sim::SimRobotDriver::create(arm7().model, driver_options);
  EXPECT_TRUE(driver) << driver.error().message;
  return RobotServer::create(std::move(driver).value(), std::move(options));
}

grpc::Status execute_plan(v1::RobotService::Stub& stub, const v1::Lease& lease,
                          const std::string& id, std::vector<core::JointWaypoint> waypoints) {
  auto trajectory = core::Trajectory::create(*arm7().model, std::move(waypoints));
  EXPECT_TRUE(trajectory) << trajectory.error().message;
  if (!trajectory) return grpc::Status(grpc::StatusCode::INTERNAL, "no trajectory");
  v1::ExecutePlanRequest request;
  request.set_lease_id(lease.lease_id());
  EXPECT_TRUE(fill_plan_message(id, *trajectory, *request.mutable_plan()).ok());
  v1::ExecutePlanResponse response;
  return stub.ExecutePlan(context().get(), request, &response);
}

TEST(RobotCollisionAuthority, TheFingersClosingOnTheBoxAtTheGraspAreAccepted) {
  auto server = create_arm7_server();
  ASSERT_TRUE(server) << server.error().message;
  auto stub = stub_for(**server);
  const std::vector<core::JointWaypoint> waypoints =
      pick_and_place(demo_like_task(kPlace.z() + kUp.z()));
  ASSERT_EQ(waypoints.size(), 7u);
  // Why the guard leaves the box out of its static scene: with the box as an obstacle the
  // fingers closing on it at the grasp are a contact.
  {
    auto workspace = geometry::load_workspace(core::default_workspace_file("arm7"));
    ASSERT_TRUE(workspace) << workspace.error().message;
    auto checker = geometry::make_collision_checker(arm7(), *workspace);
    ASSERT_TRUE(checker) << checker.error().message;
    auto trajectory = core::Trajectory::create(*arm7().model, waypoints);
    ASSERT_TRUE(trajectory) << trajectory.error().message;
    auto report = geometry::check_trajectory(*checker, *trajectory);
    ASSERT_TRUE(report) << report.error().message;
    ASSERT_FALSE(report->collision_free());
    EXPECT_EQ(report->collisions.front().other, "box");
  }
  // The lease is taken after the offline check above and outlives the whole motion (this test
  // sends no heartbeat; under a loaded sanitizer build the check and the run take many seconds).
  const v1::Lease lease = acquire(*stub, "alice", 120'000'000'000);
  const grpc::Status status = execute_plan(*stub, lease, "pick-and-place", waypoints);
  ASSERT_TRUE(status.ok()) << status.error_message();
  // It runs to the end: the arm comes to rest at the retreat.
  const Eigen::VectorXd retreat = waypoints.back().q;
  const v1::RobotState rest = stream_until(
      *stub,
      [&retreat](const v1::RobotState& s) {
        return s.mode() == v1::ROBOT_MODE_IDLE && (q_of(s) - retreat).cwiseAbs().maxCoeff() < 1e-3;
      },
      30.0);
  EXPECT_LT((q_of(rest) - retreat).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(RobotCollisionAuthority, TheBoxCarriedThroughTheTrayIsRefusedNamingIt) {
  auto server = create_arm7_server();
  ASSERT_TRUE(server) << server.error().message;
  auto stub = stub_for(**server);
  const v1::Lease lease = acquire(*stub);
  // Carried at the grip centre 35 mm above the bench: the box's bottom (25 mm below the grip)
  // 10 mm inside the tray, the fingers' tips (5 mm below) still 10 mm above it.
  const grpc::Status status =
      execute_plan(*stub, lease, "box-through-tray", pick_and_place(demo_like_task(0.035)));
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("trajectory 'box-through-tray' rejected: "
                                                "trajectory collides: at t="));
  EXPECT_THAT(status.error_message(), HasSubstr("the carried 'box' touches 'tray' (depth "));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_LT((q_of(read_state(*stub)) - arm7_ready()).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(RobotCollisionAuthority, WithoutTheBoxTheArmItselfIsStillCheckedAgainstTheTray) {
  auto server = create_arm7_server();
  ASSERT_TRUE(server) << server.error().message;
  auto stub = stub_for(**server);
  const v1::Lease lease = acquire(*stub);
  // The box is no obstacle, the tray still is: the fingers driven 20 mm into it with the
  // gripper open (nothing grasped) are refused, a link named.
  const std::vector<TaskPose> into_tray = {
      {kBox + kUp, 1.0}, {Eigen::Vector3d(kBox.x(), kBox.y(), 0.0), std::nullopt}};
  const grpc::Status status =
      execute_plan(*stub, lease, "fingers-into-tray", pick_and_place(into_tray));
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr(" link '"));
  EXPECT_THAT(status.error_message(), HasSubstr("touches 'tray' (depth "));
  EXPECT_THAT(status.error_message(), Not(HasSubstr("'box'")));
  // GetInfo hands clients the whole workspace, the box included.
  v1::RobotInfo info;
  ASSERT_TRUE(stub->GetInfo(context().get(), v1::GetInfoRequest(), &info).ok());
  EXPECT_THAT(info.workspace_yaml(), HasSubstr("graspable: true"));
}

}  // namespace
}  // namespace telear::net::test
