// The simulated robot: trajectories and stops.

#include "simulated_robot_fixture.hpp"

namespace telear::sim {
namespace {

using ::testing::HasSubstr;

TEST_F(SimulatedRobotTrajectoryTest, FollowsATrajectoryWithSmallTrackingError) {
  auto robot = make_at(q_start);
  const core::Trajectory trajectory = make_trajectory(q_start);
  auto ack = robot->execute("pick-1", trajectory);
  ASSERT_TRUE(ack.ok()) << ack.error().message;
  EXPECT_FALSE(ack->duplicate);
  EXPECT_EQ(ack->record.status, core::TrajectoryStatus::kRunning);
  const double t_start = robot->time();
  double max_error = 0.0, last_progress = 0.0;
  bool progress_in_order = true;
  MotionWatch watch(*model);
  run_for(*robot, trajectory.duration() + 0.2, [&](const core::RobotState& s) {
    watch(s);
    if (s.mode != core::RobotMode::kTrajectory) return;
    EXPECT_EQ(s.trajectory_id, "pick-1");
    const core::TrajectoryPoint reference = trajectory.sample(s.time - t_start);
    max_error = std::max(max_error, (s.q - reference.q).cwiseAbs().maxCoeff());
    progress_in_order = progress_in_order && s.trajectory_progress >= last_progress;
    last_progress = s.trajectory_progress;
    EXPECT_NEAR(s.trajectory_progress, (s.time - t_start) / trajectory.duration(), 1e-9);
  });
  EXPECT_LT(max_error, 1e-9);
  EXPECT_TRUE(progress_in_order);
  EXPECT_GT(last_progress, 0.99);
  EXPECT_LE(watch.velocity_ratio, 1.0 + 1e-6);
  EXPECT_LE(watch.acceleration_ratio, 1.0 + 1e-6);
  const core::RobotState end = robot->state();
  EXPECT_EQ(end.mode, core::RobotMode::kIdle);
  EXPECT_TRUE(end.trajectory_id.empty());
  EXPECT_EQ(end.q, trajectory.waypoints().back().q);
  const auto record = robot->trajectory_record("pick-1");
  ASSERT_TRUE(record);
  EXPECT_EQ(record->status, core::TrajectoryStatus::kCompleted);
  EXPECT_NEAR(record->finished_at, t_start + trajectory.duration(), 2 * kDt);
  // The last waypoint closes the gripper, which then closes at its own speed.
  EXPECT_EQ(end.gripper_target, 0.0);
  EXPECT_TRUE(end.gripper_moving);
  run_for(*robot, 1.0);
  EXPECT_EQ(robot->state().gripper, 0.0);
}

TEST_F(SimulatedRobotTrajectoryTest, FollowsATrajectoryThroughViaPointsWithinTheLimits) {
  auto robot = make_at(q_start);
  auto trajectory =
      core::Trajectory::create(*model, {{q_start},
                                        {deg({30, 20, -30, 40, 60, 90}), 0.0, std::nullopt, true},
                                        {deg({-20, 50, -90, -30, 10, 0})}});
  ASSERT_TRUE(trajectory.ok()) << trajectory.error().message;
  ASSERT_TRUE(trajectory->passes_through(1));
  auto ack = robot->execute("via-1", *trajectory);
  ASSERT_TRUE(ack.ok()) << ack.error().message;
  const double t_start = robot->time();
  double max_error = 0.0;
  MotionWatch watch(*model);
  run_for(*robot, trajectory->duration() + 0.2, [&](const core::RobotState& s) {
    watch(s);
    if (s.mode != core::RobotMode::kTrajectory) return;
    max_error =
        std::max(max_error, (s.q - trajectory->sample(s.time - t_start).q).cwiseAbs().maxCoeff());
  });
  EXPECT_LT(max_error, 1e-9);
  EXPECT_LE(watch.velocity_ratio, 1.0 + 1e-6);
  EXPECT_LE(watch.acceleration_ratio, 1.0 + 1e-6);
  EXPECT_EQ(robot->state().q, trajectory->waypoints().back().q);
}

TEST_F(SimulatedRobotTrajectoryTest, FollowsTimedWaypointsByInterpolatingTheSamples) {
  auto robot = make_at(q_start);
  const core::Trajectory trajectory = make_trajectory(q_start);
  const double h = 0.01;  // 100 Hz
  auto samples = trajectory.sampled(1.0 / h);
  ASSERT_TRUE(samples.ok());
  const Eigen::VectorXd q_end = samples->q.back();
  ASSERT_TRUE(robot->execute("timed-1", *samples).ok());
  const double t_start = robot->time();
  double max_error = 0.0;
  run_for(*robot, trajectory.duration() + 0.2, [&](const core::RobotState& s) {
    if (s.mode != core::RobotMode::kTrajectory) return;
    max_error =
        std::max(max_error, (s.q - trajectory.sample(s.time - t_start).q).cwiseAbs().maxCoeff());
  });
  // Linear interpolation of a motion with acceleration a misses it by at most a h^2 / 8.
  EXPECT_LT(max_error, model->max_accelerations().maxCoeff() * h * h / 8.0 + 1e-9);
  EXPECT_EQ(robot->state().q, q_end);
  EXPECT_EQ(robot->trajectory_record("timed-1")->status, core::TrajectoryStatus::kCompleted);
}

TEST_F(SimulatedRobotTrajectoryTest, MovesTheLastBitToAStartWithinTheTolerance) {
  Eigen::VectorXd q0 = q_start;
  q0[1] += 0.005;  // within the default tolerance of 0.01 rad
  auto robot = make_at(q0);
  const core::Trajectory trajectory = make_trajectory(q_start);
  ASSERT_TRUE(robot->execute("near", trajectory).ok());
  MotionWatch watch(*model);
  run_for(*robot, trajectory.duration() + 0.5, std::ref(watch));
  EXPECT_EQ(robot->state().q, trajectory.waypoints().back().q);
  EXPECT_LE(watch.acceleration_ratio, 1.0 + 1e-6);
}

TEST_F(SimulatedRobotTrajectoryTest, RejectedTrajectoriesNeverMoveTheArm) {
  auto robot = make_at(q_start);
  const core::Trajectory trajectory = make_trajectory(q_start);
  const core::TimedWaypoints samples = trajectory.sampled(100.0).value();
  auto expect_rejected = [&](const std::string& id, const auto& input, const std::string& text) {
    SCOPED_TRACE(id);
    auto ack = robot->execute(id, input);
    ASSERT_FALSE(ack.ok());
    EXPECT_THAT(ack.error().message, HasSubstr(text));
    run_for(*robot, 0.2);
    const core::RobotState s = robot->state();
    EXPECT_EQ(s.mode, core::RobotMode::kIdle);
    EXPECT_EQ(s.q, q_start);
    EXPECT_TRUE(s.qd.isZero());
    EXPECT_FALSE(robot->trajectory_record(id));
  };

  Eigen::VectorXd far = q_start;
  far[1] += core::radians_from_degrees(10.0);
  expect_rejected("far", make_trajectory(far),
                  "trajectory 'far' rejected: it starts 10.00 deg away from the arm: joint 2 "
                  "(shoulder) is at 45.00 deg, the trajectory starts at 55.00 deg (tolerance "
                  "0.57 deg)");

  core::TimedWaypoints nan = samples;
  nan.q[3][1] = kNaN;
  expect_rejected("nan", nan,
                  "trajectory 'nan' rejected: sample[3]: joint 2 (shoulder) value is not a "
                  "finite number");

  core::TimedWaypoints beyond = samples;
  beyond.q[20][2] = core::radians_from_degrees(150.0);
  expect_rejected("beyond", beyond,
                  "sample[20]: joint 3 (elbow) would be at 150.00 deg, beyond its upper limit "
                  "of 135.00 deg");

  core::TimedWaypoints fast = samples;
  for (double& t : fast.times) t *= 0.5;
  expect_rejected("fast", fast, "beyond its max velocity of");

  core::TimedWaypoints gripper = samples;
  gripper.gripper = {{0.0, 2.0}};
  expect_rejected("gripper", gripper, "gripper event[0]: opening 2 is outside [0, 1]");

  // A Trajectory planned for a faster arm is too fast for this one.
  core::RobotModel::Description d;
  d.name = model->name();
  d.joints = model->joints();
  for (core::Joint& joint : d.joints) {
    joint.limits.max_velocity *= 2.0;
    joint.limits.max_acceleration *= 2.0;
  }
  const core::RobotModel fast_model = core::RobotModel::create(d).value();
  const core::Trajectory fast_trajectory =
      core::Trajectory::create(fast_model, trajectory.waypoints()).value();
  expect_rejected("fast-model", fast_trajectory,
                  "trajectory 'fast-model' rejected: segment waypoint[0] to waypoint[1]");

  expect_rejected("", trajectory, "trajectory rejected: its id is empty");
  expect_rejected(std::string(200, 'x'), trajectory,
                  "its id is 200 characters long, more than the maximum of 128");
}

TEST_F(SimulatedRobotTrajectoryTest, ABusyArmRejectsAnotherTrajectoryOrAJog) {
  auto robot = make_at(q_start);
  const core::Trajectory trajectory = make_trajectory(q_start);
  ASSERT_TRUE(robot->execute("a", trajectory).ok());
  run_for(*robot, 0.1);
  auto second = robot->execute("b", trajectory);
  ASSERT_FALSE(second.ok());
  EXPECT_THAT(second.error().message,
              HasSubstr("trajectory 'b' rejected: trajectory 'a' is running; cancel it first"));
  const Status jog = robot->jog_velocity(Eigen::VectorXd::Zero(6), robot->time() + 1.0);
  ASSERT_FALSE(jog.ok());
  EXPECT_THAT(jog.error().message, HasSubstr("jog rejected: trajectory 'a' is running"));
  EXPECT_FALSE(robot->trajectory_record("b"));
  robot->cancel();
  run_for(*robot, 1.0);
  // While jogging a trajectory is refused too.
  ASSERT_TRUE(robot->jog_velocity(Eigen::VectorXd::Constant(6, 0.01), robot->time() + 1.0).ok());
  auto third = robot->execute("c", make_trajectory(robot->state().q));
  ASSERT_FALSE(third.ok());
  EXPECT_THAT(third.error().message,
              HasSubstr("trajectory 'c' rejected: the arm is jogging; wait until it is at rest"));
}

TEST_F(SimulatedRobotTrajectoryTest, ATrajectoryIdIsExecutedOnlyOnce) {
  auto robot = make_at(q_start);
  const core::Trajectory trajectory = make_trajectory(q_start);
  ASSERT_TRUE(robot->execute("move", trajectory).ok());
  run_for(*robot, 0.2);
  // A retry while it runs: acknowledged as a duplicate, the running one is not restarted.
  auto retry = robot->execute("move", trajectory);
  ASSERT_TRUE(retry.ok());
  EXPECT_TRUE(retry->duplicate);
  EXPECT_EQ(retry->record.status, core::TrajectoryStatus::kRunning);
  EXPECT_NEAR(robot->state().trajectory_time, 0.2, 1e-9);
  run_for(*robot, trajectory.duration());
  const Eigen::VectorXd q_end = trajectory.waypoints().back().q;
  ASSERT_EQ(robot->state().q, q_end);
  // A retry after it completed does not move the arm back to the start and through again.
  auto late_retry = robot->execute("move", trajectory);
  ASSERT_TRUE(late_retry.ok());
  EXPECT_TRUE(late_retry->duplicate);
  EXPECT_EQ(late_retry->record.status, core::TrajectoryStatus::kCompleted);
  run_for(*robot, trajectory.duration(), [&](const core::RobotState& s) {
    ASSERT_EQ(s.mode, core::RobotMode::kIdle);
    ASSERT_EQ(s.q, q_end);
  });
}

// [SECTION] Stops

TEST_F(SimulatedRobotTrajectoryTest, CancelStopsOnThePathWithinTheStoppingTime) {
  const Eigen::VectorXd q_goal = deg({90, 0, 0, 90, 60, 90});
  auto robot = make_at(q_start);
  const core::Trajectory trajectory =
      core::Trajectory::create(*model, {{q_start}, {q_goal}}).value();
  ASSERT_TRUE(robot->execute("long", trajectory).ok());
  run_for(*robot, trajectory.duration() / 2);  // cruising
  const Eigen::VectorXd qd = robot->state().qd;
  const double T = stopping_time(qd, model->max_accelerations());
  const double cancelled_at = robot->time();
  robot->cancel("operator cancel");
  EXPECT_EQ(robot->state().mode, core::RobotMode::kStopping);
  EXPECT_EQ(robot->state().stop_reason, "operator cancel");
  const Eigen::VectorXd direction = (q_goal - q_start).normalized();
  double off_path = 0.0, at_rest_since = -1.0;
  MotionWatch watch(*model);
  run_for(*robot, T + 0.2, [&](const core::RobotState& s) {
    watch(s);
    const Eigen::VectorXd dq = s.q - q_start;
    off_path = std::max(off_path, (dq - direction * direction.dot(dq)).norm());
    if (s.mode == core::RobotMode::kIdle && at_rest_since < 0.0) at_rest_since = s.time;
  });
  EXPECT_NEAR(at_rest_since - cancelled_at, T, 2 * kDt);
  EXPECT_LT(off_path, 1e-9);
  EXPECT_LE(watch.acceleration_ratio, 1.0 + 1e-9);
  const auto record = robot->trajectory_record("long");
  EXPECT_EQ(record->status, core::TrajectoryStatus::kCancelled);
  EXPECT_EQ(record->message, "operator cancel");
  EXPECT_LT(robot->state().q[0], q_goal[0]);
}

TEST_F(SimulatedRobotTest, TheWorstCaseStopFromMaxVelocityTakesMaxVelocityOverAcceleration) {
  auto robot = make_at(deg({0, 0, 0, 0, -60, 0}));
  ASSERT_TRUE(robot->jog_velocity(model->max_velocities(), robot->time() + 2.0).ok());
  run_for(*robot, 0.5);
  // Every joint at full speed.
  ASSERT_LT((robot->state().qd - model->max_velocities()).cwiseAbs().maxCoeff(), 1e-12);
  const double cancelled_at = robot->time();
  robot->cancel("lease lapsed");
  double at_rest_since = -1.0;
  run_for(*robot, 0.5, [&](const core::RobotState& s) {
    if (s.mode == core::RobotMode::kIdle && at_rest_since < 0.0) at_rest_since = s.time;
  });
  const double worst =
      worst_case_stopping_time(model->max_velocities(), model->max_accelerations());
  RecordProperty("worst_case_stopping_time_ms", std::to_string(worst * 1000.0));
  EXPECT_NEAR(at_rest_since - cancelled_at, worst, 2 * kDt);
}

TEST_F(SimulatedRobotTrajectoryTest, EStopHaltsAtOnceLatchesAndRejectsCommands) {
  auto robot = make_at(q_start);
  const core::Trajectory trajectory = make_trajectory(q_start);
  ASSERT_TRUE(robot->execute("run", trajectory).ok());
  run_for(*robot, 0.5);
  const Eigen::VectorXd q_halt = robot->state().q;
  ASSERT_FALSE(robot->state().qd.isZero());
  robot->estop("operator pressed the e-stop");
  core::RobotState s = robot->state();
  EXPECT_EQ(s.mode, core::RobotMode::kEStopped);
  EXPECT_TRUE(s.estop);
  EXPECT_TRUE(s.qd.isZero());
  EXPECT_EQ(s.q, q_halt);
  EXPECT_EQ(robot->trajectory_record("run")->status, core::TrajectoryStatus::kAborted);
  EXPECT_EQ(robot->trajectory_record("run")->message, "e-stop: operator pressed the e-stop");
  run_for(*robot, 1.0);
  EXPECT_EQ(robot->state().q, q_halt);

  const std::string latched =
      "the e-stop is engaged (since t = 100.5 s: operator pressed the "
      "e-stop); reset it once the arm is at rest";
  const Status jog = robot->jog_velocity(Eigen::VectorXd::Zero(6), robot->time() + 1.0);
  ASSERT_FALSE(jog.ok());
  EXPECT_THAT(jog.error().message, HasSubstr("jog rejected: " + latched));
  auto increment = robot->jog(core::JointIncrement{0, 0.1}, robot->time() + 1.0);
  ASSERT_FALSE(increment.ok());
  EXPECT_THAT(increment.error().message, HasSubstr(latched));
  auto again = robot->execute("after", make_trajectory(q_halt));
  ASSERT_FALSE(again.ok());
  EXPECT_THAT(again.error().message, HasSubstr("trajectory 'after' rejected: " + latched));
  const Status gripper = robot->set_gripper(0.0);
  ASSERT_FALSE(gripper.ok());
  EXPECT_THAT(gripper.error().message, HasSubstr("gripper command rejected: " + latched));
  robot->estop("pressed again");
  EXPECT_EQ(robot->state().estop_reason, "operator pressed the e-stop");
  run_for(*robot, 0.2);
  EXPECT_EQ(robot->state().q, q_halt);

  ASSERT_TRUE(robot->reset_estop().ok());
  s = robot->state();
  EXPECT_EQ(s.mode, core::RobotMode::kIdle);
  EXPECT_FALSE(s.estop);
  EXPECT_EQ(s.q, q_halt);
  EXPECT_TRUE(robot->jog(core::JointIncrement{0, 0.1}, robot->time() + 1.0).ok());
}

TEST_F(SimulatedRobotTest, EStopResetIsRefusedWhileAJointStillMoves) {
  auto robot = make_at(q_start);
  ASSERT_TRUE(robot->inject_fault({1, JointFaultKind::kDrift, 0.2, 0.01}).ok());
  robot->estop("test");
  run_for(*robot, 0.2);
  EXPECT_NEAR(robot->state().q[1], q_start[1] + 0.002, 1e-9);  // creeping under the e-stop
  const Status refused = robot->reset_estop();
  ASSERT_FALSE(refused.ok());
  EXPECT_THAT(refused.error().message,
              HasSubstr("cannot reset the e-stop while the arm moves: joint 2 (shoulder) moves "
                        "at 0.57 deg/s; wait until it is at rest"));
  EXPECT_EQ(robot->state().mode, core::RobotMode::kEStopped);
  ASSERT_TRUE(robot->clear_injected_faults().ok());
  ASSERT_TRUE(robot->reset_estop().ok());
  const Eigen::VectorXd q_held = robot->state().q;
  run_for(*robot, 0.2);
  EXPECT_EQ(robot->state().q, q_held);
  EXPECT_EQ(robot->state().mode, core::RobotMode::kIdle);
}

}  // namespace
}  // namespace telear::sim
