#pragma once
// The ROS 1 side of the ROS 1 robot driver (ros1_robot_driver.hpp): one roscpp node that
// subscribes to the arm's sensor_msgs/JointState topic, sends control_msgs/FollowJointTrajectory
// (and optionally GripperCommand) goals through actionlib, and publishes what telear wants ROS
// tools to see. Everything ROS stays inside ros1_link.cpp, a C++17 unit (ROS 1 message headers do
// not compile as C++20): this header uses the standard library only, so the C++20 driver
// includes it without ROS.
//
// Health and reconnection. A monitor thread asks the master for its pid every 100 ms. The
// node's subscriptions and action clients are registered only while the master answers: when
// it goes away they are dropped (roscpp would otherwise block a caller until it returns) and
// when it is back they are registered again, so a restarted master or controller is picked up
// without restarting telear. Each change is reported through the log handler.
//
// One link per process: roscpp's node is process-wide (ros::init once, ros::shutdown once).

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace telear::drivers::ros1 {

struct LinkOptions {
  std::string master_uri;  // http://HOST:PORT; empty: $ROS_MASTER_URI
  std::string node_name = "telear_robot_server";
  std::string joint_states_topic = "/joint_states";
  std::string controller_ns = "/arm_controller/follow_joint_trajectory";
  std::string gripper_ns;  // control_msgs/GripperCommand; empty: none
  std::string ghost_topic = "/telear/ghost/joint_states";
  std::string workspace_topic = "/telear/workspace";
  // Set as the parameter robot_description beside the ghost topic (/telear/ghost/...), so a
  // robot_state_publisher in that namespace draws the ghost in RViz (docs/ros.md).
  std::string robot_description;
};

struct JointStateMessage {
  double stamp_s = 0.0;  // header stamp, ROS time (s); 0 when the publisher left it unset
  // The stamp on CLOCK_MONOTONIC (ros_clock_offset.hpp); the receipt without a stamp or with
  // one ahead of this machine's ROS clock.
  std::int64_t capture_ns = 0;
  std::vector<std::string> name;
  std::vector<double> position, velocity;
};

// One FollowJointTrajectory goal: positions only (the controller interpolates), in the
// order of joint_names, at whole nanoseconds from the goal's start (ROS durations are
// integer seconds and nanoseconds; telear's wire rounds sample times the same way).
struct TrajectoryGoal {
  std::vector<std::string> joint_names;
  std::vector<std::int64_t> times_ns;
  std::vector<std::vector<double>> positions;
};

// One workspace object as a visualization_msgs/Marker (RViz's shapes).
struct WorkspaceMarker {
  enum class Shape { kBox, kCylinder, kSphere, kMesh };
  Shape shape = Shape::kBox;
  std::string name;  // the marker's namespace
  // box: edges; cylinder: 2r, 2r, length; sphere: 2r x 3; mesh: its scale
  std::array<double, 3> scale{};
  std::array<double, 3> position{};                       // in frame_id, m
  std::array<double, 4> orientation{0.0, 0.0, 0.0, 1.0};  // quaternion x, y, z, w
  std::array<float, 3> colour{};                          // RGB 0..1
  std::string mesh_resource;                              // mesh: file:///absolute/path
};

enum class GoalEnd { kSucceeded, kAborted, kPreempted, kRejected, kLost };

struct GoalOutcome {
  GoalEnd end = GoalEnd::kLost;
  int error_code = 0;        // control_msgs' error_code (0: SUCCESSFUL)
  std::string error_string;  // the controller's, may be empty
  std::string state;         // actionlib's terminal state and its text, for messages
};

struct LinkHealth {
  bool master = false;      // the master answered the last check
  bool controller = false;  // the FollowJointTrajectory server is connected
  bool gripper = false;     // the GripperCommand server is connected (false without one)
};

// The action's feedback: where the controller wants the joints now (its setpoint) and how far
// into the goal it is.
struct GoalFeedback {
  std::vector<std::string> joint_names;
  std::vector<double> desired;  // positions, in joint_names' order
  double time_from_start_s = 0.0;
};

// What the link calls. on_goal_done and on_goal_feedback come from a thread of the link's own,
// never with a ROS lock held (see ros1_link.cpp); on_state from a ROS thread.
struct LinkHandlers {
  std::function<void(const JointStateMessage&)> on_state;
  // Once per goal, with its number from send_trajectory.
  std::function<void(std::uint64_t goal, const GoalOutcome&)> on_goal_done;
  std::function<void(std::uint64_t goal, const GoalFeedback&)> on_goal_feedback;
  std::function<void(const std::string&)> log;
};

class Link {
 public:
  // Starts the node and its monitor; the master need not be up yet. Fails (message in
  // *error) on an invalid option, or when a link was started before in this process.
  static std::unique_ptr<Link> start(const LinkOptions& options, LinkHandlers handlers,
                                     std::string* error);
  ~Link();  // cancels a running goal, shuts the node down
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  LinkHealth health() const;
  // ROS time now (s): the clock joint state stamps are on.
  double ros_now_s() const;

  // Sends the goal (replacing any active one, which is no longer tracked); returns its
  // number (> 0), or 0 when the controller is not connected.
  std::uint64_t send_trajectory(const TrajectoryGoal& goal);
  // Cancels the active goal, if any (actionlib's cancel message to the controller).
  void cancel_trajectory();
  // A GripperCommand goal; false when there is no gripper action or it is not connected.
  bool send_gripper(double position, double max_effort);

  // sensor_msgs/JointState on the ghost topic (latched: a late subscriber sees the last one).
  void publish_ghost(const std::vector<std::string>& names, const std::vector<double>& position);
  // visualization_msgs/MarkerArray on the workspace topic (latched), in frame_id.
  void publish_workspace(const std::string& frame_id, const std::vector<WorkspaceMarker>& markers);

 private:
  class Node;
  explicit Link(std::unique_ptr<Node> node);
  std::unique_ptr<Node> node_;
};

}  // namespace telear::drivers::ros1
