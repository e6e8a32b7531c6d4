// The simulated robot: construction, jogs, the gripper, the true model, faults, threads.

#include "simulated_robot_fixture.hpp"

namespace telear::sim {
namespace {

using ::testing::HasSubstr;

// [SECTION] Construction

TEST_F(SimulatedRobotTest, StartsIdleAndAtRest) {
  auto robot = make();
  const core::RobotState s = robot->state();
  EXPECT_EQ(s.mode, core::RobotMode::kIdle);
  EXPECT_EQ(s.time, kEpoch);
  EXPECT_TRUE(s.q.isZero());
  EXPECT_TRUE(s.qd.isZero());
  EXPECT_EQ(s.gripper, 1.0);
  EXPECT_FALSE(s.estop);
  EXPECT_FALSE(s.fault);
  EXPECT_TRUE(s.trajectory_id.empty());
}

TEST_F(SimulatedRobotTest, RejectsInvalidOptionsSayingWhich) {
  auto message = [&](SimulatedRobotOptions o) {
    auto robot = SimulatedRobot::create(model, clock, o);
    return robot.ok() ? std::string("accepted") : robot.error().message;
  };
  SimulatedRobotOptions o;
  o.servo_period = 0.0;
  EXPECT_THAT(message(o), HasSubstr("servo_period must be in (0, 0.1] s, got 0"));
  o = {};
  o.initial_q = *model->named_configuration("qn");
  EXPECT_THAT(message(o), HasSubstr("initial_q: joint 3 (elbow) would be at 180.00 deg, beyond "
                                    "its upper limit of 135.00 deg"));
  o = {};
  o.true_joint_offsets = Eigen::VectorXd::Zero(5);
  EXPECT_THAT(message(o),
              HasSubstr("true joint offsets: expected 6 values for robot 'puma560', got 5"));
  o = {};
  o.stop_deceleration_scale = 1.5;
  EXPECT_THAT(message(o), HasSubstr("stop_deceleration_scale must be in (0, 1], got 1.5"));
  o = {};
  o.gripper_speed = 0.0;
  EXPECT_THAT(message(o), HasSubstr("gripper_speed must be a positive finite number"));
}

// [SECTION] Jogs

TEST_F(SimulatedRobotTest, VelocityJogMovesWithinTheLimitsAndStopsAtItsExpiry) {
  auto robot = make_at(q_start);
  Eigen::VectorXd qd(6);
  qd << 0.5, -0.3, 0.4, 1.0, -1.0, 2.0;  // rad/s, each within its joint's max velocity
  const double expires_at = robot->time() + 0.5;
  ASSERT_TRUE(robot->jog_velocity(qd, expires_at).ok());
  MotionWatch watch(*model);
  Eigen::VectorXd qd_before_expiry;
  double at_rest_since = -1.0;
  run_for(*robot, 1.0, [&](const core::RobotState& s) {
    watch(s);
    if (std::abs(s.time - (expires_at - 0.01)) < kDt / 2) qd_before_expiry = s.qd;
    if (s.mode == core::RobotMode::kIdle && at_rest_since < 0.0) at_rest_since = s.time;
  });
  // Up to speed before the expiry, then a controlled stop that starts at the expiry.
  ASSERT_EQ(qd_before_expiry.size(), 6);
  EXPECT_LT((qd_before_expiry - qd).cwiseAbs().maxCoeff(), 1e-12);
  const double T = stopping_time(qd, model->max_accelerations());
  EXPECT_NEAR(at_rest_since, expires_at + T, 2 * kDt);
  EXPECT_LE(watch.velocity_ratio, 1.0 + 1e-12);
  EXPECT_LE(watch.acceleration_ratio, 1.0 + 1e-9);
  EXPECT_TRUE(watch.within_limits);
  const core::RobotState end = robot->state();
  EXPECT_TRUE(end.qd.isZero());
  run_for(*robot, 0.5);
  EXPECT_EQ(robot->state().q, end.q);
}

TEST_F(SimulatedRobotTest, AJogPastItsExpiryIsIgnored) {
  auto robot = make_at(q_start);
  const double now = robot->time();
  const Status s = robot->jog_velocity(Eigen::VectorXd::Constant(6, 0.1), now - 0.05);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message,
              HasSubstr("jog ignored: it expired at t = 99.95 s, 0.05 s before it arrived at "
                        "t = 100 s"));
  auto increment = robot->jog(core::JointIncrement{0, 0.1}, now);
  ASSERT_FALSE(increment.ok());
  EXPECT_THAT(increment.error().message, HasSubstr("jog ignored: it expired"));
  auto far = robot->jog(core::JointIncrement{0, 0.1}, now + 60.0);
  ASSERT_FALSE(far.ok());
  EXPECT_THAT(far.error().message, HasSubstr("later than the maximum of 10 s"));
  run_for(*robot, 0.5);
  EXPECT_EQ(robot->state().q, q_start);
  EXPECT_EQ(robot->state().mode, core::RobotMode::kIdle);
}

TEST_F(SimulatedRobotTest, VelocityJogIsValidated) {
  auto robot = make_at(q_start);
  const double expires = robot->time() + 1.0;
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(6);
  qd[0] = 2.0;
  Status s = robot->jog_velocity(qd, expires);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message,
              HasSubstr("joint velocity jog rejected: joint 1 (waist) at 114.59 deg/s exceeds "
                        "its max velocity of 80.00 deg/s"));
  qd[0] = kNaN;
  s = robot->jog_velocity(qd, expires);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message, HasSubstr("joint 1 (waist) value is not a finite number"));
  s = robot->jog_velocity(Eigen::VectorXd::Zero(5), expires);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message, HasSubstr("expected 6, got 5"));
  run_for(*robot, 0.2);
  EXPECT_EQ(robot->state().q, q_start);
}

TEST_F(SimulatedRobotTest, VelocityJogBrakesOntoAJointLimitWithoutAFault) {
  Eigen::VectorXd q0 = q_start;
  q0[0] = core::radians_from_degrees(150.0);
  auto robot = make_at(q0);
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(6);
  qd[0] = model->max_velocities()[0];
  ASSERT_TRUE(robot->jog_velocity(qd, robot->time() + 3.0).ok());
  MotionWatch watch(*model);
  run_for(*robot, 1.0, std::ref(watch));
  EXPECT_TRUE(watch.within_limits);
  EXPECT_LE(watch.acceleration_ratio, 1.0 + 1e-9);
  const core::RobotState s = robot->state();
  EXPECT_NEAR(s.q[0], model->upper_limits()[0], 1e-9);
  EXPECT_EQ(s.qd[0], 0.0);
  EXPECT_FALSE(s.fault);
}

TEST_F(SimulatedRobotTest, JointIncrementsArriveExactlyAndAccumulate) {
  auto robot = make_at(q_start);
  auto outcome = robot->jog(core::JointIncrement{1, 0.1}, robot->time() + 2.0);
  ASSERT_TRUE(outcome.ok()) << outcome.error().message;
  MotionWatch watch(*model);
  run_for(*robot, 1.0, std::ref(watch));
  EXPECT_EQ(robot->state().mode, core::RobotMode::kIdle);
  EXPECT_EQ(robot->state().q[1], q_start[1] + 0.1);
  // A stream of small increments, each sent before the last one arrived, adds up exactly.
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(robot->jog(core::JointIncrement{2, 0.01}, robot->time() + 0.5).ok());
    run_for(*robot, 0.005, std::ref(watch));
  }
  EXPECT_EQ(robot->state().mode, core::RobotMode::kJogging);
  run_for(*robot, 1.0, std::ref(watch));
  EXPECT_EQ(robot->state().mode, core::RobotMode::kIdle);
  EXPECT_NEAR(robot->state().q[2], q_start[2] + 0.1, 1e-12);
  EXPECT_LE(watch.velocity_ratio, 1.0 + 1e-12);
  EXPECT_LE(watch.acceleration_ratio, 1.0 + 1e-9);
}

TEST_F(SimulatedRobotTest, CartesianJogMovesTheToolByTheIncrement) {
  const Eigen::VectorXd q0 = deg({10, 45, -60, 20, 40, 10});
  auto robot = make_at(q0);
  const Eigen::Isometry3d T0 = core::tool_pose(*model, q0);
  auto outcome =
      robot->jog(core::CartesianIncrement{core::MotionFrame::kBase, {0, 0, 0.01}, {0, 0, 0}},
                 robot->time() + 2.0);
  ASSERT_TRUE(outcome.ok()) << outcome.error().message;
  run_for(*robot, 1.0);
  const Eigen::Isometry3d T1 = core::tool_pose(*model, robot->state().q);
  EXPECT_LT((T1.translation() - T0.translation() - Eigen::Vector3d(0, 0, 0.01)).norm(), 1e-6);
  EXPECT_LT((T1.linear() - T0.linear()).cwiseAbs().maxCoeff(), 1e-6);
}

// Issue 12: the real (simulated) arm of every shipped URDF arm jogs in the base, wrist and
// tool frames like the PUMA: the tool moves by the increment, expressed in that frame, within
// the velocity and acceleration limits (the 7-DOF arm through its redundancy resolution).
TEST_F(SimulatedRobotTest, CartesianJogsOfTheShippedUrdfArmsInEveryFrame) {
  for (const char* name : {"ur6", "arm7"}) {
    auto description = core::load_robot_description({name, "", {}});
    ASSERT_TRUE(description) << description.error().message;
    model = description->model;
    const auto ready = model->named_configuration("ready");
    ASSERT_TRUE(ready) << name;
    for (const core::MotionFrame frame :
         {core::MotionFrame::kBase, core::MotionFrame::kWrist, core::MotionFrame::kTool}) {
      auto robot = make_at(*ready);
      const Eigen::Isometry3d T0 = core::tool_pose(*model, *ready);
      const Eigen::Vector3d step(0.01, -0.005, 0.008);
      auto outcome =
          robot->jog(core::CartesianIncrement{frame, step, {0, 0, 0}}, robot->time() + 2.0);
      ASSERT_TRUE(outcome.ok()) << name << ": " << outcome.error().message;
      MotionWatch watch(*model);
      run_for(*robot, 1.5, std::ref(watch));
      const Eigen::Isometry3d T1 = core::tool_pose(*model, robot->state().q);
      // The step in base axes, in the flange's axes (wrist) or in the tool's (tool), at the
      // start: a pure translation keeps the orientation.
      core::KinematicsData data(*model);
      core::forward_kinematics(*model, data, *ready);
      const Eigen::Matrix3d axes = frame == core::MotionFrame::kBase ? Eigen::Matrix3d::Identity()
                                   : frame == core::MotionFrame::kWrist
                                       ? Eigen::Matrix3d(data.T_base_link.back().linear())
                                       : Eigen::Matrix3d(T0.linear());
      const Eigen::Vector3d expected = axes * step;
      EXPECT_LT((T1.translation() - T0.translation() - expected).norm(), 1e-6)
          << name << " frame " << static_cast<int>(frame);
      EXPECT_LT((T1.linear() - T0.linear()).cwiseAbs().maxCoeff(), 1e-6) << name;
      EXPECT_TRUE(watch.within_limits) << name;
      EXPECT_LE(watch.velocity_ratio, 1.0 + 1e-9) << name;
    }
  }
}

TEST_F(SimulatedRobotTest, ARejectedJogNeverMovesTheArm) {
  const Eigen::VectorXd q0 = deg({0, 100, -60, 0, 30, 0});
  auto robot = make_at(q0);
  auto outcome =
      robot->jog(core::JointIncrement{1, core::radians_from_degrees(20)}, robot->time() + 2.0);
  ASSERT_FALSE(outcome.ok());
  EXPECT_THAT(outcome.error().message,
              HasSubstr("jog rejected: joint 2 (shoulder) would be at 120.00 deg, beyond its "
                        "upper limit of 110.00 deg"));
  run_for(*robot, 0.5);
  EXPECT_EQ(robot->state().q, q0);
  EXPECT_EQ(robot->state().mode, core::RobotMode::kIdle);
}

TEST_F(SimulatedRobotTest, AJogThatExpiresBeforeArrivingStopsShortOfItsTarget) {
  auto robot = make_at(q_start);
  ASSERT_TRUE(robot->jog(core::JointIncrement{0, 1.0}, robot->time() + 0.3).ok());
  MotionWatch watch(*model);
  run_for(*robot, 2.0, std::ref(watch));
  const core::RobotState s = robot->state();
  EXPECT_EQ(s.mode, core::RobotMode::kIdle);
  EXPECT_GT(s.q[0], q_start[0] + 0.05);
  EXPECT_LT(s.q[0], q_start[0] + 0.5);
  EXPECT_LE(watch.acceleration_ratio, 1.0 + 1e-9);
}

// [SECTION] Gripper

TEST_F(SimulatedRobotTest, GripperMovesAtItsFiniteSpeed) {
  SimulatedRobotOptions options;
  options.gripper_speed = 0.5;
  auto robot = make(options);
  ASSERT_TRUE(robot->set_gripper(0.0).ok());
  run_for(*robot, 1.0);
  EXPECT_NEAR(robot->state().gripper, 0.5, 1e-9);
  EXPECT_TRUE(robot->state().gripper_moving);
  run_for(*robot, 1.1);
  EXPECT_EQ(robot->state().gripper, 0.0);
  EXPECT_FALSE(robot->state().gripper_moving);
  Status s = robot->set_gripper(1.5);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message,
              HasSubstr("gripper command rejected: opening 1.5 is outside [0, 1] (0 closed, 1 "
                        "open)"));
  s = robot->set_gripper(kNaN);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message, HasSubstr("opening nan is outside"));
  // Cancel halts the gripper where it is.
  ASSERT_TRUE(robot->set_gripper(1.0).ok());
  run_for(*robot, 0.4);
  robot->cancel();
  run_for(*robot, 0.5);
  EXPECT_NEAR(robot->state().gripper, 0.2, 1e-9);
  EXPECT_FALSE(robot->state().gripper_moving);
}

// [SECTION] True model

TEST_F(SimulatedRobotTest, TheTrueModelIsOffsetWhileTheReadingsStayNominal) {
  SimulatedRobotOptions options;
  options.initial_q = q_start;
  options.true_joint_offsets = deg({0.5, -0.3, 0.2, 1.0, -0.5, 0.25});
  auto robot = make(options);
  ASSERT_NE(robot->true_model().get(), model.get());
  EXPECT_EQ(robot->true_model()->name(), "puma560");
  std::mt19937_64 rng(42);
  for (int i = 0; i < 20; ++i) {
    const Eigen::VectorXd q = test::random_configuration(*model, rng);
    const Eigen::Matrix4d T_true = core::tool_pose(*robot->true_model(), q).matrix();
    const Eigen::Matrix4d T_nominal_offset =
        core::tool_pose(*model, q + options.true_joint_offsets).matrix();
    EXPECT_LT(test::max_abs_diff(T_true, T_nominal_offset), 1e-12);
  }
  // The real tool is measurably elsewhere than where the nominal model puts it.
  const double miss = (core::tool_pose(*robot->true_model(), q_start).translation() -
                       core::tool_pose(*model, q_start).translation())
                          .norm();
  EXPECT_GT(miss, 0.003);  // 5.6 mm
  EXPECT_EQ(robot->state().q, q_start);
  EXPECT_EQ(make()->true_model().get(), model.get());  // no offsets: the nominal model
}

// [SECTION] Fault injection

TEST_F(SimulatedRobotTrajectoryTest, InjectedFaultsShowAsTrackingError) {
  auto robot = make_at(q_start);
  ASSERT_TRUE(robot->inject_fault({0, JointFaultKind::kStuck}).ok());
  ASSERT_TRUE(robot->inject_fault({1, JointFaultKind::kLag, 0.1}).ok());
  const core::Trajectory trajectory = make_trajectory(q_start);
  ASSERT_TRUE(robot->execute("faulty", trajectory).ok());
  double lag_error = 0.0;
  run_for(*robot, trajectory.duration() + 0.01, [&](const core::RobotState& s) {
    EXPECT_EQ(s.q[0], q_start[0]);  // stuck
    lag_error = std::max(lag_error, std::abs(s.q_commanded[1] - s.q[1]));
    EXPECT_EQ(s.q[2], s.q_commanded[2]);  // healthy joints track exactly
  });
  const core::RobotState end = robot->state();
  EXPECT_NEAR(end.q_commanded[0] - end.q[0], trajectory.waypoints().back().q[0] - q_start[0],
              1e-12);
  EXPECT_GT(lag_error, 0.01);
  run_for(*robot, 1.0);  // the lagging joint catches up once the command rests
  EXPECT_LT(std::abs(robot->state().q_commanded[1] - robot->state().q[1]), 1e-4);

  const Status bad = robot->inject_fault({6, JointFaultKind::kStuck});
  ASSERT_FALSE(bad.ok());
  EXPECT_THAT(bad.error().message, HasSubstr("joint index 6 is out of range (0 to 5)"));
  ASSERT_TRUE(robot->clear_injected_faults().ok());
  EXPECT_EQ(robot->state().q, robot->state().q_commanded);
}

TEST_F(SimulatedRobotTest, ADriftIntoAJointLimitIsClampedAndLatchesAFault) {
  Eigen::VectorXd q0 = q_start;
  q0[1] = core::radians_from_degrees(109.0);
  auto robot = make_at(q0);
  ASSERT_TRUE(robot->inject_fault({1, JointFaultKind::kDrift, 0.2, 0.1}).ok());
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(6);
  qd[0] = 0.5;
  ASSERT_TRUE(robot->jog_velocity(qd, robot->time() + 5.0).ok());
  MotionWatch watch(*model);
  run_for(*robot, 1.0, std::ref(watch));
  EXPECT_TRUE(watch.within_limits);
  const core::RobotState s = robot->state();
  EXPECT_EQ(s.q[1], model->upper_limits()[1]);
  ASSERT_TRUE(s.fault);
  EXPECT_THAT(*s.fault, HasSubstr("joint 2 (shoulder) measured at 110.0"));
  EXPECT_THAT(*s.fault,
              HasSubstr("beyond its upper limit of 110.00 deg: hard-clamped to the limit"));
  // The fault stopped the jog long before its expiry.
  EXPECT_EQ(s.mode, core::RobotMode::kIdle);
  EXPECT_TRUE(s.qd.isZero());
  robot->clear_fault();
  EXPECT_FALSE(robot->state().fault);
}

// [SECTION] Threads

TEST(SimulatedRobotThreads, CommandsFromSeveralThreadsWhileAServoThreadSteps) {
  const core::RobotModelPtr model = test::puma560();
  auto created = SimulatedRobot::create(model, std::make_shared<SteadyClock>());
  ASSERT_TRUE(created.ok());
  SimulatedRobot& robot = **created;
  ServoThread servo(robot, 0.001);
  std::atomic<bool> all_within_limits = true;
  std::vector<std::thread> clients;
  for (int c = 0; c < 4; ++c) {
    clients.emplace_back([&, c] {
      std::mt19937_64 rng(1000 + c);
      std::uniform_int_distribution<int> pick(0, 4);
      std::uniform_real_distribution<double> unit(-1.0, 1.0);
      for (int i = 0; i < 150; ++i) {
        const double expires = robot.time() + 0.05;
        switch (pick(rng)) {
          case 0: {
            Eigen::VectorXd qd(6);
            for (int j = 0; j < 6; ++j) qd[j] = 0.5 * unit(rng) * model->max_velocities()[j];
            (void)robot.jog_velocity(qd, expires);
            break;
          }
          case 1:
            (void)robot.jog(core::JointIncrement{c, 0.02 * unit(rng)}, expires);
            break;
          case 2:
            robot.cancel("client " + std::to_string(c));
            break;
          case 3:
            (void)robot.set_gripper(0.5 + 0.5 * unit(rng));
            break;
          default:
            break;
        }
        const core::RobotState s = robot.state();
        for (int j = 0; j < 6; ++j) {
          if (s.q[j] < model->lower_limits()[j] || s.q[j] > model->upper_limits()[j]) {
            all_within_limits = false;
          }
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    });
  }
  for (auto& client : clients) client.join();
  robot.estop("end of test");
  servo.stop();
  const core::RobotState end = robot.state();
  EXPECT_TRUE(all_within_limits);
  EXPECT_EQ(end.mode, core::RobotMode::kEStopped);
  EXPECT_FALSE(end.fault);
  EXPECT_GT(end.time, 0.0);
}

}  // namespace
}  // namespace telear::sim
