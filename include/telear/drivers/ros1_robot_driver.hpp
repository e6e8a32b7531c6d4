#pragma once
// A RobotDriver over ROS 1 (docs/ros.md): the arm a lab already drives through ROS, with the
// interfaces ros_control's joint_trajectory_controller, ur_robot_driver and franka_ros offer.
//
//   state       sensor_msgs/JointState on --joint-states, mapped by joint name into the model's
//               (the URDF's) order: any order, extra joints ignored, a missing one a fault that
//               names it. capture_ns is the message's stamp on the server clock
//               (src/drivers/ros1/ros_clock_offset.hpp), its receipt when it has none.
//   trajectory  one control_msgs/FollowJointTrajectory goal per accepted trajectory or plan: the
//               samples exactly as the server accepted them (PreviewPlan's), names in model
//               order, time_from_start from the samples. The record follows the action: its
//               feedback gives the state's q_commanded (the controller's setpoint, so a monitor
//               sees the tracking error) and trajectory time; running until the result; succeeded
//               -> completed; aborted or rejected -> aborted with the controller's error_string;
//               preempted -> cancelled with the reason telear gave.
//   stop        Cancel, a lapsed lease, the e-stop: actionlib's cancel at once.
//   jogs        short goals from the measured position to the jog's target (a motion command's,
//               or the velocity held until the expiry), timed by core's trajectory
//               parameterization; at the expiry a goal still running is cancelled (the
//               controller's own controlled stop).
//   gripper     control_msgs/GripperCommand with --gripper-action: the opening fraction as the
//               gap in metres (the robot file's max opening), also for a plan's gripper events.
//   rehearsal   what the operator rehearses, for RViz, on the ghost topic (sensor_msgs/JointState,
//               latched): the lease holder's ghost as the console's heartbeat carries it (about
//               12 Hz while it changes), and each previewed plan's samples played in real time at
//               30 Hz (the ghost waits until the plan has played); the server's workspace as a
//               visualization_msgs/MarkerArray on the workspace topic (latched), in the robot's
//               root link frame; the robot's URDF as the parameter robot_description beside the
//               ghost topic, so that Debian's robot_state_publisher run there (tf_prefix ghost)
//               gives RViz the ghost's frames.
//   faults      the master not answering, no joint states for silence_timeout_s, a missing
//               joint, the action server not connected: every motion is refused with that
//               reason and the state's `fault` says it; all clear themselves when ROS is back
//               (the link re-registers by itself, ros1_link.hpp).
//
// ROS types stay in the C++17 unit behind drivers/ros1/ros1_link.hpp; this header has none.

#include <cstdint>
#include <memory>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_driver.hpp"

namespace telear::drivers {

struct Ros1DriverOptions {
  std::string master_uri;  // http://HOST:PORT; empty: $ROS_MASTER_URI
  std::string joint_states_topic = "/joint_states";
  std::string controller_ns = "/arm_controller/follow_joint_trajectory";
  std::string gripper_ns;  // control_msgs/GripperCommand action; empty: no gripper
  std::string ghost_topic = "/telear/ghost/joint_states";
  std::string workspace_topic = "/telear/workspace";
  double ghost_rate_hz = 30.0;     // the previewed plan played at this rate
  double silence_timeout_s = 0.5;  // no joint states for longer: a fault
  double start_tolerance = 0.01;   // rad or m, a trajectory's start against the arm
  double jog_sample_rate_hz = 100.0;
  double gripper_max_effort_n = 0.0;  // GripperCommand's max_effort (0: the controller's)
  double max_jog_duration_s = 10.0;
};

class Ros1RobotDriver;

// Starts the ROS node (the master need not be up: the driver reports a fault until it is).
// Fails on bad options, a robot without joint names, or when the driver was not built
// (TELEAR_WITH_ROS1=OFF): the message says which.
Result<std::unique_ptr<core::RobotDriver>> make_ros1_robot_driver(
    const core::RobotDescription& description, const Ros1DriverOptions& options);

// Whether this build has the ROS 1 driver.
bool ros1_driver_built();

}  // namespace telear::drivers
