#pragma once
// The DDS side of the ROS 2 robot driver (ros2_robot_driver.hpp): one Cyclone DDS participant on
// the ROS domain that reads the arm's sensor_msgs/msg/JointState topic and writes
// trajectory_msgs/msg/JointTrajectory to a JointTrajectoryController, with the names, types and
// QoS a ROS 2 node on rmw_cyclonedds_cpp would use (docs/ros2.md):
//
//   joint states   reader, best effort, volatile, keep last 1: it matches a reliable or a
//                  best-effort publisher (joint_state_broadcaster's system-default QoS is
//                  reliable on Cyclone, sensor-data QoS is best effort), and only the newest
//                  state matters.
//   trajectory     writer, reliable, volatile, keep last 10: rclcpp's default publisher QoS,
//                  which the controller's subscription (system default) accepts.
//   ghost          writer, reliable, transient local, keep last 1: ROS 2's "latched".
//
// All in XCDR1 (plain CDR), the one data representation rmw_cyclonedds accepts. The DDS types
// are the C code idlc generated from data/ros2/idl (cmake/TelearRos2.cmake); this header has
// none, so the driver's unit sees only the standard library.
//
// Threads: a waitset thread takes joint states as they arrive and calls the handler with a copy
// (no DDS lock held), and logs the topics' matches (a controller or an arm appearing or going).
// Every other member may be called from any thread.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace telear::drivers::ros2 {

struct LinkOptions {
  std::uint32_t domain_id = 0;
  // DDS topic names (rt/..., ros2_names.hpp).
  std::string joint_states_topic = "rt/joint_states";
  std::string trajectory_topic = "rt/joint_trajectory_controller/joint_trajectory";
  std::string ghost_topic = "rt/telear/ghost/joint_states";
};

struct JointStateMessage {
  std::int64_t stamp_ns = 0;  // header stamp, ns since the epoch (ROS time); 0 when unset
  std::vector<std::string> name;
  std::vector<double> position, velocity;
};

// One JointTrajectory: positions only (the controller interpolates), in the order of
// joint_names, at whole nanoseconds from the start; the header stamp is zero, "start now".
struct TrajectoryMessage {
  std::vector<std::string> joint_names;
  std::vector<std::int64_t> times_ns;
  std::vector<std::vector<double>> positions;
};

class Link {
 public:
  using JointStatesHandler = std::function<void(const JointStateMessage&)>;
  using LogHandler = std::function<void(const std::string&)>;

  // Creates the participant (configured by $CYCLONEDDS_URI, as for any Cyclone DDS program),
  // the topics and endpoints, and starts the waitset thread. Fails (message in *error) when
  // Cyclone DDS refuses any of them.
  static std::unique_ptr<Link> start(const LinkOptions& options, JointStatesHandler on_state,
                                     LogHandler log, std::string* error);
  ~Link();  // stops the thread, deletes the participant (a reliable writer lingers to deliver)
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  // How many readers match the trajectory writer: 0 means no controller would hear it.
  int trajectory_subscribers() const;
  // Writes one trajectory; false (and a log line) when DDS refuses it.
  bool publish_trajectory(const TrajectoryMessage& message);
  // sensor_msgs/msg/JointState on the ghost topic, stamped with the system clock.
  void publish_ghost(const std::vector<std::string>& names, const std::vector<double>& position);

 private:
  class Participant;
  explicit Link(std::unique_ptr<Participant> participant);
  std::unique_ptr<Participant> participant_;
};

}  // namespace telear::drivers::ros2
