#include "telear/sim/simulated_robot.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "telear/core/angles.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/sim/servo_thread.hpp"
#include "test_util/test_util.hpp"

namespace telear::sim {
namespace {

using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDt = 0.001;  // the default servo period

Eigen::VectorXd deg(std::initializer_list<double> values) {
  Eigen::VectorXd q(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double v : values) q[i++] = core::radians_from_degrees(v);
  return q;
}

// Watches every period's state: speeds against the max velocities, the change of velocity
// over one period against the max accelerations, positions against the limits.
struct MotionWatch {
  explicit MotionWatch(const core::RobotModel& model) : model(model) {}
  void operator()(const core::RobotState& s) {
    for (int j = 0; j < model.dof(); ++j) {
      velocity_ratio = std::max(velocity_ratio, std::abs(s.qd[j]) / model.max_velocities()[j]);
      if (previous_qd.size() != 0) {
        acceleration_ratio = std::max(acceleration_ratio, std::abs(s.qd[j] - previous_qd[j]) /
                                                              (kDt * model.max_accelerations()[j]));
      }
      within_limits =
          within_limits && s.q[j] >= model.lower_limits()[j] && s.q[j] <= model.upper_limits()[j];
    }
    previous_qd = s.qd;
  }
  const core::RobotModel& model;
  Eigen::VectorXd previous_qd;
  double velocity_ratio = 0.0;
  double acceleration_ratio = 0.0;
  bool within_limits = true;
};

class SimulatedRobotTest : public ::testing::Test {
 protected:
  // A start time other than 0, so that a mix-up of robot time and time since start shows.
  static constexpr double kEpoch = 100.0;

  std::unique_ptr<SimulatedRobot> make(SimulatedRobotOptions options = {}) {
    auto robot = SimulatedRobot::create(model, clock, std::move(options));
    EXPECT_TRUE(robot.ok()) << (robot.ok() ? "" : robot.error().message);
    return robot.ok() ? std::move(robot).value() : nullptr;
  }
  std::unique_ptr<SimulatedRobot> make_at(const Eigen::VectorXd& q) {
    SimulatedRobotOptions options;
    options.initial_q = q;
    return make(options);
  }

  // Advances simulated time period by period, updating the robot and handing each state to
  // `each`. The clock is set from a count, not summed, so no rounding accumulates.
  void run_for(SimulatedRobot& robot, double seconds,
               const std::function<void(const core::RobotState&)>& each = nullptr) {
    const double start = clock->now();
    const long periods = std::lround(seconds / kDt);
    for (long k = 1; k <= periods; ++k) {
      clock->set(start + static_cast<double>(k) * kDt);
      robot.update();
      if (each) each(robot.state());
    }
  }

  core::RobotModelPtr model = test::puma560();
  std::shared_ptr<ManualClock> clock = std::make_shared<ManualClock>(kEpoch);
  const Eigen::VectorXd q_start = deg({0, 45, -60, 0, 30, 0});  // away from singularities
};

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

// [SECTION] Trajectories

class SimulatedRobotTrajectoryTest : public SimulatedRobotTest {
 protected:
  core::Trajectory make_trajectory(const Eigen::VectorXd& from) {
    auto trajectory = core::Trajectory::create(
        *model,
        {{from}, {deg({30, 20, -30, 40, 60, 90})}, {deg({-20, 50, -90, -30, 10, 0}), 0.0, 0.0}});
    EXPECT_TRUE(trajectory.ok());
    return std::move(trajectory).value();
  }
};

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
