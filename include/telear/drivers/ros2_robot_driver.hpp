#pragma once
// A RobotDriver over ROS 2 (docs/ros2.md), spoken as DDS directly: Debian 12 has no rclcpp, but
// ROS 2 with rmw_cyclonedds_cpp is DDS on the wire, so telear joins the ROS 2 graph as a Cyclone
// DDS participant with ROS 2's topic and type names. The arm is a ros2_control one: its
// joint_state_broadcaster and a JointTrajectoryController's topic interface.
//
//   state       sensor_msgs/msg/JointState on --ros2-joint-states (DDS rt/joint_states, type
//               sensor_msgs::msg::dds_::JointState_), mapped by joint name into the model's (the
//               URDF's) order: any order, extra joints ignored, a missing one a fault that
//               names it. capture_ns is the receipt time on the server clock less the message's
//               age (this machine's system clock minus its stamp; an age outside 0 .. the
//               silence timeout, as from another clock or sim time, counts as 0).
//   trajectory  one trajectory_msgs/msg/JointTrajectory per accepted trajectory or plan on
//               <controller>/joint_trajectory: the samples exactly as the server accepted them
//               (PreviewPlan's), names in model order, time_from_start from the samples,
//               positions only, header stamp zero ("start now"). A topic has no result, so
//               telear decides the end: completed once the trajectory's duration has passed and
//               the arm is within the start tolerance of its last point on every joint; aborted
//               when it is not there goal_time_s after the duration (the message names the
//               farthest joint).
//   stop        Cancel, a lapsed lease, the e-stop (also at rest): a hold trajectory at once:
//               one point, the arm's last measured position (while that is stale, the running
//               trajectory's setpoint now), time_from_start 0, stamp 0 -- what the controller
//               itself commands when an action goal is cancelled (its set_hold_position()). An
//               empty JointTrajectory is NOT a stop in ROS 2: the controller rejects it ("Empty
//               trajectory received.") and keeps moving. The stop is recorded when published.
//   jogs        short trajectories from the measured position to the jog's target (as the ROS 1
//               driver's goals); at the expiry one still running is stopped with the hold.
//   gripper     none (ros2_control's gripper controllers take actions): SetGripper is refused;
//               a plan's gripper events that keep the reported opening (0) are no-ops, one that
//               changes it refuses the plan, as the ROS 1 driver without a gripper action.
//   rehearsal   on the ghost topic (sensor_msgs/msg/JointState, transient local: ROS 2's
//               "latched"): the lease holder's ghost from the heartbeat, and each previewed
//               plan's samples played at 30 Hz, then its last sample held. No workspace markers
//               (visualization_msgs/Marker differs between ROS 2 releases).
//   faults      no joint states yet, none for silence_timeout_s, a missing joint, no subscriber
//               on the trajectory topic (the controller is not active): every motion is refused
//               with that reason and the state's `fault` says it; all clear themselves when the
//               arm is back.
//
// DDS types stay in the units under src/drivers/ros2/; this header has none.

#include <cstdint>
#include <memory>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_driver.hpp"

namespace telear::drivers {

struct Ros2DriverOptions {
  int domain_id = -1;  // 0 .. 232; -1: $ROS_DOMAIN_ID, or 0 when it is unset
  std::string joint_states_topic = "/joint_states";         // ROS names: DDS rt/joint_states
  std::string controller = "/joint_trajectory_controller";  // takes <controller>/joint_trajectory
  std::string ghost_topic = "/telear/ghost/joint_states";
  double ghost_rate_hz = 30.0;     // the previewed plan played at this rate
  double silence_timeout_s = 0.5;  // no joint states for longer: a fault
  double start_tolerance = 0.01;   // rad or m: a trajectory's start against the arm, and its end
  double goal_time_s = 1.0;        // after the duration, the arm has this long to reach the end
  double jog_sample_rate_hz = 100.0;
  double max_jog_duration_s = 10.0;
};

// Joins the DDS domain (the arm need not be up: the driver reports a fault until it is). Fails
// on bad options (a topic that is not an absolute ROS name, a domain outside 0..232), a robot
// without joint names, a DDS participant that cannot be created (CYCLONEDDS_URI), or when the
// driver was not built (TELEAR_WITH_ROS2=OFF): the message says which.
Result<std::unique_ptr<core::RobotDriver>> make_ros2_robot_driver(
    const core::RobotDescription& description, const Ros2DriverOptions& options);

// Whether this build has the ROS 2 driver.
bool ros2_driver_built();

}  // namespace telear::drivers
