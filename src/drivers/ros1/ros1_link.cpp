// C++17: ROS 1 headers (see ros1_link.hpp).
#include "drivers/ros1/ros1_link.hpp"
#include "drivers/ros1/ros_clock_offset.hpp"

#include <actionlib/client/simple_action_client.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/GripperCommandAction.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <visualization_msgs/MarkerArray.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace telear::drivers::ros1 {
namespace {

using TrajectoryClient = actionlib::SimpleActionClient<control_msgs::FollowJointTrajectoryAction>;
using GripperClient = actionlib::SimpleActionClient<control_msgs::GripperCommandAction>;

std::atomic<bool> g_link_started{false};

constexpr auto kMonitorPeriod = std::chrono::milliseconds(100);

GoalEnd goal_end(const actionlib::SimpleClientGoalState& state) {
  switch (state.state_) {
    case actionlib::SimpleClientGoalState::SUCCEEDED:
      return GoalEnd::kSucceeded;
    case actionlib::SimpleClientGoalState::ABORTED:
      return GoalEnd::kAborted;
    case actionlib::SimpleClientGoalState::PREEMPTED:
    case actionlib::SimpleClientGoalState::RECALLED:
      return GoalEnd::kPreempted;
    case actionlib::SimpleClientGoalState::REJECTED:
      return GoalEnd::kRejected;
    default:
      return GoalEnd::kLost;
  }
}

}  // namespace

class Link::Node {
 public:
  Node(LinkOptions options, LinkHandlers handlers)
      : options_(std::move(options)), handlers_(std::move(handlers)), log_(handlers_.log) {}

  void start() {
    handle_ = std::make_unique<ros::NodeHandle>();
    spinner_ = std::make_unique<ros::AsyncSpinner>(2);
    spinner_->start();
    dispatcher_ = std::thread([this] { dispatch(); });
    monitor_ = std::thread([this] { monitor(); });
  }

  ~Node() {
    {
      std::lock_guard lock(events_mutex_);
      stopping_ = true;
    }
    events_changed_.notify_all();
    if (monitor_.joinable()) monitor_.join();
    {
      std::lock_guard lock(clients_mutex_);
      if (trajectory_ && trajectory_active_) trajectory_->cancelGoal();
      unregister_locked();
    }
    if (spinner_) spinner_->stop();
    if (dispatcher_.joinable()) dispatcher_.join();
    ros::shutdown();
  }

  LinkHealth health() const { return {master_.load(), controller_.load(), gripper_.load()}; }

  std::uint64_t send_trajectory(const TrajectoryGoal& goal) {
    control_msgs::FollowJointTrajectoryGoal message;
    trajectory_msgs::JointTrajectory& trajectory = message.trajectory;
    // A zero stamp: the controller starts the trajectory when the goal arrives.
    trajectory.joint_names = goal.joint_names;
    trajectory.points.resize(goal.times_ns.size());
    for (std::size_t k = 0; k < goal.times_ns.size(); ++k) {
      trajectory.points[k].positions = goal.positions[k];
      trajectory.points[k].time_from_start.fromNSec(goal.times_ns[k]);
    }
    std::lock_guard lock(clients_mutex_);
    if (!trajectory_ || !trajectory_->isServerConnected()) return 0;
    const std::uint64_t number = ++last_goal_;
    trajectory_active_ = true;
    trajectory_->sendGoal(
        message,
        [this, number](const actionlib::SimpleClientGoalState& state,
                       const control_msgs::FollowJointTrajectoryResultConstPtr& result) {
          GoalOutcome outcome;
          outcome.end = goal_end(state);
          outcome.state =
              state.toString() + (state.getText().empty() ? "" : ": " + state.getText());
          if (result) {
            outcome.error_code = result->error_code;
            outcome.error_string = result->error_string;
          }
          post([this, number, outcome] { handlers_.on_goal_done(number, outcome); });
        },
        TrajectoryClient::SimpleActiveCallback(),
        [this, number](const control_msgs::FollowJointTrajectoryFeedbackConstPtr& message) {
          if (!handlers_.on_goal_feedback) return;
          GoalFeedback feedback;
          feedback.joint_names = message->joint_names;
          feedback.desired = message->desired.positions;
          feedback.time_from_start_s = message->desired.time_from_start.toSec();
          post([this, number, feedback] { handlers_.on_goal_feedback(number, feedback); });
        });
    return number;
  }

  void cancel_trajectory() {
    std::lock_guard lock(clients_mutex_);
    if (trajectory_ && trajectory_active_) trajectory_->cancelGoal();
    trajectory_active_ = false;
  }

  bool send_gripper(double position, double max_effort) {
    std::lock_guard lock(clients_mutex_);
    if (!gripper_client_ || !gripper_client_->isServerConnected()) return false;
    control_msgs::GripperCommandGoal goal;
    goal.command.position = position;
    goal.command.max_effort = max_effort;
    gripper_client_->sendGoal(goal);
    return true;
  }

  void publish_ghost(const std::vector<std::string>& names, const std::vector<double>& position) {
    sensor_msgs::JointState message;
    message.header.stamp = ros::Time::now();
    message.name = names;
    message.position = position;
    std::lock_guard lock(clients_mutex_);
    last_ghost_ = message;
    if (ghost_) ghost_.publish(message);
  }

  void publish_workspace(const std::string& frame_id, const std::vector<WorkspaceMarker>& markers) {
    visualization_msgs::MarkerArray array;
    const ros::Time now = ros::Time::now();
    for (std::size_t i = 0; i < markers.size(); ++i) {
      const WorkspaceMarker& from = markers[i];
      visualization_msgs::Marker marker;
      marker.header.frame_id = frame_id;
      marker.header.stamp = now;
      marker.ns = from.name;
      marker.id = static_cast<int>(i);
      marker.action = visualization_msgs::Marker::ADD;
      switch (from.shape) {
        case WorkspaceMarker::Shape::kBox:
          marker.type = visualization_msgs::Marker::CUBE;
          break;
        case WorkspaceMarker::Shape::kCylinder:
          marker.type = visualization_msgs::Marker::CYLINDER;
          break;
        case WorkspaceMarker::Shape::kSphere:
          marker.type = visualization_msgs::Marker::SPHERE;
          break;
        case WorkspaceMarker::Shape::kMesh:
          marker.type = visualization_msgs::Marker::MESH_RESOURCE;
          marker.mesh_resource = from.mesh_resource;
          break;
      }
      marker.pose.position.x = from.position[0];
      marker.pose.position.y = from.position[1];
      marker.pose.position.z = from.position[2];
      marker.pose.orientation.x = from.orientation[0];
      marker.pose.orientation.y = from.orientation[1];
      marker.pose.orientation.z = from.orientation[2];
      marker.pose.orientation.w = from.orientation[3];
      marker.scale.x = from.scale[0];
      marker.scale.y = from.scale[1];
      marker.scale.z = from.scale[2];
      marker.color.r = from.colour[0];
      marker.color.g = from.colour[1];
      marker.color.b = from.colour[2];
      marker.color.a = 1.0f;
      array.markers.push_back(marker);
    }
    std::lock_guard lock(clients_mutex_);
    last_workspace_ = array;
    if (workspace_) workspace_.publish(array);
  }

 private:
  // Events for the driver leave ROS's threads through this queue: actionlib calls back with
  // its goal list locked, and the driver sends goals with its own state locked; handing the
  // outcome to another thread keeps the two locks from ever being taken in opposite orders.
  void post(std::function<void()> event) {
    {
      std::lock_guard lock(events_mutex_);
      events_.push_back(std::move(event));
    }
    events_changed_.notify_all();
  }

  void dispatch() {
    std::unique_lock lock(events_mutex_);
    for (;;) {
      events_changed_.wait(lock, [this] { return stopping_ || !events_.empty(); });
      if (events_.empty()) return;  // stopping, nothing left
      auto event = std::move(events_.front());
      events_.pop_front();
      lock.unlock();
      event();
      lock.lock();
    }
  }

  void monitor() {
    bool said_waiting = false;
    bool controller_was = false, gripper_was = false;
    std::unique_lock events_lock(events_mutex_);
    while (!stopping_) {
      events_lock.unlock();
      const bool master = ros::master::check();
      {
        std::lock_guard lock(clients_mutex_);
        if (master && !registered_) {
          register_locked();
          log_("connected to the ROS master at " + ros::master::getURI());
          said_waiting = false;
        } else if (!master && registered_) {
          unregister_locked();
          log_("lost the ROS master at " + ros::master::getURI() +
               ": motion refused until it is back");
        } else if (!master && !said_waiting) {
          log_("waiting for the ROS master at " + ros::master::getURI());
          said_waiting = true;
        }
        master_ = master;
        controller_ = registered_ && trajectory_->isServerConnected();
        gripper_ = registered_ && gripper_client_ && gripper_client_->isServerConnected();
      }
      if (controller_ != controller_was) {
        log_(std::string(controller_ ? "connected to" : "lost") + " the action server " +
             options_.controller_ns + " (control_msgs/FollowJointTrajectory)");
        controller_was = controller_;
      }
      if (!options_.gripper_ns.empty() && gripper_ != gripper_was) {
        log_(std::string(gripper_ ? "connected to" : "lost") + " the gripper action server " +
             options_.gripper_ns + " (control_msgs/GripperCommand)");
        gripper_was = gripper_;
      }
      events_lock.lock();
      events_changed_.wait_for(events_lock, kMonitorPeriod, [this] { return stopping_; });
    }
  }

  void register_locked() {
    joint_states_ = handle_->subscribe<sensor_msgs::JointState>(
        options_.joint_states_topic, 20,
        [this](const sensor_msgs::JointState::ConstPtr& message) { on_joint_state(*message); },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
    trajectory_ = std::make_unique<TrajectoryClient>(*handle_, options_.controller_ns, false);
    trajectory_active_ = false;
    if (!options_.gripper_ns.empty()) {
      gripper_client_ = std::make_unique<GripperClient>(*handle_, options_.gripper_ns, false);
    }
    ghost_ = handle_->advertise<sensor_msgs::JointState>(options_.ghost_topic, 1, true);
    if (last_ghost_) ghost_.publish(*last_ghost_);
    workspace_ =
        handle_->advertise<visualization_msgs::MarkerArray>(options_.workspace_topic, 1, true);
    if (last_workspace_) workspace_.publish(*last_workspace_);
    if (!options_.robot_description.empty()) {
      const std::string& topic = options_.ghost_topic;
      const std::string ns = topic.substr(0, topic.find_last_of('/'));
      ros::param::set(ns + "/robot_description", options_.robot_description);
    }
    registered_ = true;
  }

  void unregister_locked() {
    joint_states_.shutdown();
    ghost_.shutdown();
    workspace_.shutdown();
    trajectory_.reset();
    gripper_client_.reset();
    trajectory_active_ = false;
    registered_ = false;
  }

  void on_joint_state(const sensor_msgs::JointState& message) {
    const RosClockOffset::Reading receipt = clock_offset_.read();
    JointStateMessage state;
    const auto stamp_ns = static_cast<std::int64_t>(message.header.stamp.toNSec());
    state.stamp_s = message.header.stamp.toSec();
    state.capture_ns = RosClockOffset::capture_ns(stamp_ns, receipt);
    state.name = message.name;
    state.position = message.position;
    state.velocity = message.velocity;
    handlers_.on_state(state);
  }

  LinkOptions options_;
  LinkHandlers handlers_;
  RosClockOffset clock_offset_;
  std::function<void(const std::string&)> log_;

  std::unique_ptr<ros::NodeHandle> handle_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;

  std::mutex clients_mutex_;  // the registrations below
  bool registered_ = false;
  ros::Subscriber joint_states_;
  ros::Publisher ghost_;
  std::optional<sensor_msgs::JointState> last_ghost_;
  ros::Publisher workspace_;
  std::optional<visualization_msgs::MarkerArray> last_workspace_;
  std::unique_ptr<TrajectoryClient> trajectory_;
  bool trajectory_active_ = false;
  std::unique_ptr<GripperClient> gripper_client_;
  std::uint64_t last_goal_ = 0;

  std::atomic<bool> master_{false}, controller_{false}, gripper_{false};

  std::mutex events_mutex_;
  std::condition_variable events_changed_;
  std::deque<std::function<void()>> events_;
  bool stopping_ = false;
  std::thread dispatcher_, monitor_;
};

std::unique_ptr<Link> Link::start(const LinkOptions& options, LinkHandlers handlers,
                                  std::string* error) {
  std::string master_uri = options.master_uri;
  if (master_uri.empty()) {
    const char* environment = std::getenv("ROS_MASTER_URI");
    if (environment != nullptr) master_uri = environment;
  }
  if (master_uri.empty()) {
    *error = "no ROS master: give --ros-master http://HOST:PORT or set ROS_MASTER_URI";
    return nullptr;
  }
  if (master_uri.rfind("http://", 0) != 0) {
    *error = "the ROS master URI must look like http://HOST:PORT, got '" + master_uri + "'";
    return nullptr;
  }
  for (const auto& [what, name] : {std::pair{"--joint-states", options.joint_states_topic},
                                   std::pair{"--controller", options.controller_ns}}) {
    if (name.empty() || name.find_first_of(" \t\n") != std::string::npos) {
      *error = std::string(what) + " must be a ROS name, got '" + name + "'";
      return nullptr;
    }
  }
  // roscpp's node is the process's: a second link (or the camera link's node, which checks
  // the same) would silently share the first one's name and master.
  if (g_link_started.exchange(true) || ros::isInitialized()) {
    *error = "a ROS 1 node was already started in this process (roscpp allows one)";
    return nullptr;
  }
  ros::M_string remappings{{"__master", master_uri}};
  ros::init(remappings, options.node_name,
            ros::init_options::NoSigintHandler | ros::init_options::NoRosout);
  // A registration with a master that went away gives up after this instead of blocking the
  // monitor forever; the monitor tries again on its next round.
  ros::master::setRetryTimeout(ros::WallDuration(1.0));
  auto node = std::make_unique<Node>(options, std::move(handlers));
  node->start();
  return std::unique_ptr<Link>(new Link(std::move(node)));
}

Link::Link(std::unique_ptr<Node> node) : node_(std::move(node)) {}
Link::~Link() = default;

LinkHealth Link::health() const {
  return node_->health();
}

double Link::ros_now_s() const {
  return ros::Time::now().toSec();
}

std::uint64_t Link::send_trajectory(const TrajectoryGoal& goal) {
  return node_->send_trajectory(goal);
}

void Link::cancel_trajectory() {
  node_->cancel_trajectory();
}

bool Link::send_gripper(double position, double max_effort) {
  return node_->send_gripper(position, max_effort);
}

void Link::publish_ghost(const std::vector<std::string>& names,
                         const std::vector<double>& position) {
  node_->publish_ghost(names, position);
}

void Link::publish_workspace(const std::string& frame_id,
                             const std::vector<WorkspaceMarker>& markers) {
  node_->publish_workspace(frame_id, markers);
}

}  // namespace telear::drivers::ros1
