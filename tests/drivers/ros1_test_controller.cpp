// A ROS 1 arm for the driver's tests: a real actionlib control_msgs/FollowJointTrajectory server
// (as ros_control's joint_trajectory_controller offers) and a sensor_msgs/JointState publisher,
// written here because Debian packages no controller. C++17 (ROS 1 headers).
//
//   ros1_test_controller --joints a,b,c [--initial 0,0,0] [--ns
//   /arm_controller/follow_joint_trajectory]
//                        [--log FILE] [--abort-after S --abort-message TEXT] [--silent-file FILE]
//                        [--rate HZ] [--gripper-ns NS] [--lag S]
//
// It publishes the joints in an order of its own (reversed) with an extra joint in the middle,
// as a real robot's joint_states often carries the gripper or other joints. A goal is executed
// by interpolating its points linearly in time (names mapped into its own order). With
// --abort-after it aborts each goal after S seconds with error_code PATH_TOLERANCE_VIOLATED and
// --abort-message as error_string. While --silent-file exists it publishes nothing. The action's
// feedback carries the setpoint (desired), the arm (actual) and their difference; with --lag
// the arm follows its setpoint S seconds late, as a real servo lags.
//
// --log appends one JSON object per line: {"event":"goal","received_ns":..,"joint_names":[..],
// "times_ns":[..],"positions":[[..],..]}, {"event":"cancel","received_ns":..},
// {"event":"gripper","received_ns":..,"position":..}; received_ns on CLOCK_MONOTONIC, the clock
// telear's servers stamp with, so a test compares them with the server's times. The first line on
// stdout is "controller ready" once the action server runs.

#include <actionlib/server/simple_action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/GripperCommandAction.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <sys/stat.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::int64_t monotonic_ns() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) parts.push_back(part);
  return parts;
}

bool file_exists(const std::string& path) {
  struct stat info {};
  return !path.empty() && stat(path.c_str(), &info) == 0;
}

struct Options {
  std::vector<std::string> joints;
  std::vector<double> initial;
  std::string ns = "/arm_controller/follow_joint_trajectory";
  std::string gripper_ns;
  std::string log;
  double abort_after_s = -1.0;
  std::string abort_message;
  std::string silent_file;
  double rate_hz = 100.0;
  double lag_s = 0.0;  // the arm follows its setpoint this much later
};

class Controller {
 public:
  explicit Controller(Options options)
      : options_(std::move(options)), q_(options_.initial), server_(handle_, options_.ns, false) {
    server_.registerGoalCallback([this] { accept(); });
    server_.registerPreemptCallback([this] { on_preempt(); });
    publisher_ = handle_.advertise<sensor_msgs::JointState>("/joint_states", 10);
    if (!options_.gripper_ns.empty()) {
      gripper_ = std::make_unique<GripperServer>(handle_, options_.gripper_ns, false);
      gripper_->registerGoalCallback([this] { on_gripper(); });
      gripper_->start();
    }
    server_.start();
    timer_ = handle_.createWallTimer(ros::WallDuration(1.0 / options_.rate_hz),
                                     [this](const ros::WallTimerEvent&) { step(); });
  }

 private:
  using Server = actionlib::SimpleActionServer<control_msgs::FollowJointTrajectoryAction>;
  enum class End { kNone, kSucceeded, kAborted };
  using GripperServer = actionlib::SimpleActionServer<control_msgs::GripperCommandAction>;

  void log(const std::string& line) {
    if (options_.log.empty()) return;
    std::ofstream out(options_.log, std::ios::app);
    out << line << "\n";
  }

  void accept() {
    const std::int64_t received = monotonic_ns();
    auto goal = server_.acceptNewGoal();
    std::ostringstream line;
    line.precision(17);
    line << R"({"event":"goal","received_ns":)" << received << R"(,"joint_names":[)";
    const auto& trajectory = goal->trajectory;
    for (std::size_t i = 0; i < trajectory.joint_names.size(); ++i) {
      line << (i ? "," : "") << '"' << trajectory.joint_names[i] << '"';
    }
    line << R"(],"times_ns":[)";
    for (std::size_t k = 0; k < trajectory.points.size(); ++k) {
      line << (k ? "," : "") << trajectory.points[k].time_from_start.toNSec();
    }
    line << R"(],"positions":[)";
    for (std::size_t k = 0; k < trajectory.points.size(); ++k) {
      line << (k ? "," : "") << "[";
      const auto& positions = trajectory.points[k].positions;
      for (std::size_t j = 0; j < positions.size(); ++j) line << (j ? "," : "") << positions[j];
      line << "]";
    }
    line << "]}";
    log(line.str());
    // Columns of the goal in this controller's joint order; a joint it does not have: abort.
    // (actionlib calls back with its own lock held: its calls are made outside ours.)
    std::vector<int> columns(options_.joints.size(), -1);
    for (std::size_t j = 0; j < options_.joints.size(); ++j) {
      const auto at = std::find(trajectory.joint_names.begin(), trajectory.joint_names.end(),
                                options_.joints[j]);
      if (at == trajectory.joint_names.end()) {
        control_msgs::FollowJointTrajectoryResult result;
        result.error_code = control_msgs::FollowJointTrajectoryResult::INVALID_JOINTS;
        result.error_string = "goal lacks joint " + options_.joints[j];
        {
          std::lock_guard lock(mutex_);
          active_ = false;
        }
        server_.setAborted(result, result.error_string);
        return;
      }
      columns[j] = static_cast<int>(at - trajectory.joint_names.begin());
    }
    std::lock_guard lock(mutex_);
    columns_ = columns;
    trajectory_ = trajectory;
    start_ = ros::WallTime::now();
    active_ = true;
  }

  void on_preempt() {
    log(R"({"event":"cancel","received_ns":)" + std::to_string(monotonic_ns()) + "}");
    {
      std::lock_guard lock(mutex_);
      active_ = false;  // holds where it is: the controller's stop
    }
    server_.setPreempted();
  }

  void on_gripper() {
    auto goal = gripper_->acceptNewGoal();
    std::ostringstream line;
    line << R"({"event":"gripper","received_ns":)" << monotonic_ns() << R"(,"position":)"
         << goal->command.position << "}";
    log(line.str());
    control_msgs::GripperCommandResult result;
    result.position = goal->command.position;
    result.reached_goal = true;
    gripper_->setSucceeded(result);
  }

  // Follows the active goal, then publishes the joints.
  void step() {
    End end = End::kNone;
    sensor_msgs::JointState message;
    control_msgs::FollowJointTrajectoryFeedback feedback;
    {
      std::lock_guard lock(mutex_);
      if (active_) end = follow(feedback);
      if (end != End::kNone) active_ = false;
      // Reversed, with a joint the robot description does not have in the middle.
      for (std::size_t j = q_.size(); j-- > 0;) {
        message.name.push_back(options_.joints[j]);
        message.position.push_back(q_[j]);
        message.velocity.push_back(0.0);
        if (j == q_.size() / 2) {
          message.name.push_back("extra_conveyor_joint");
          message.position.push_back(42.0);
          message.velocity.push_back(0.0);
        }
      }
    }
    if (!feedback.joint_names.empty()) server_.publishFeedback(feedback);
    if (end == End::kSucceeded) server_.setSucceeded(control_msgs::FollowJointTrajectoryResult());
    if (end == End::kAborted) {
      control_msgs::FollowJointTrajectoryResult result;
      result.error_code = control_msgs::FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED;
      result.error_string = options_.abort_message;
      server_.setAborted(result, options_.abort_message);
    }
    if (file_exists(options_.silent_file)) return;
    message.header.stamp = ros::Time::now();
    publisher_.publish(message);
  }

  // The goal's positions at t (s from its start), in this controller's joint order.
  std::vector<double> setpoint(double t) const {
    const auto& points = trajectory_.points;
    std::vector<double> q(q_.size());
    std::size_t k = 1;
    while (k + 1 < points.size() && points[k].time_from_start.toSec() < t) ++k;
    const double t0 = k > 0 ? points[k - 1].time_from_start.toSec() : 0.0;
    const double t1 = points[std::min(k, points.size() - 1)].time_from_start.toSec();
    const double s = t1 > t0 ? std::clamp((t - t0) / (t1 - t0), 0.0, 1.0) : 1.0;
    for (std::size_t j = 0; j < q.size(); ++j) {
      const double a = points[k > 0 ? k - 1 : 0].positions[columns_[j]];
      const double b = points[std::min(k, points.size() - 1)].positions[columns_[j]];
      q[j] = a + (b - a) * s;
    }
    return q;
  }

  // Moves q_ along the goal, --lag seconds behind its setpoint (under mutex_), fills the
  // action's feedback; says how the goal ended, if it did.
  End follow(control_msgs::FollowJointTrajectoryFeedback& feedback) {
    const double t = (ros::WallTime::now() - start_).toSec();
    const auto& points = trajectory_.points;
    if (options_.abort_after_s >= 0.0 && t >= options_.abort_after_s) return End::kAborted;
    const double end_s = points.back().time_from_start.toSec();
    if (t >= end_s + options_.lag_s) {
      for (std::size_t j = 0; j < q_.size(); ++j) q_[j] = points.back().positions[columns_[j]];
      return End::kSucceeded;
    }
    q_ = setpoint(std::max(t - options_.lag_s, 0.0));
    feedback.header.stamp = ros::Time::now();
    feedback.joint_names = options_.joints;
    feedback.desired.positions = setpoint(std::min(t, end_s));
    feedback.desired.time_from_start = ros::Duration(std::min(t, end_s));
    feedback.actual.positions = q_;
    for (std::size_t j = 0; j < q_.size(); ++j) {
      feedback.error.positions.push_back(feedback.desired.positions[j] - q_[j]);
    }
    return End::kNone;
  }

  Options options_;
  std::vector<double> q_;
  ros::NodeHandle handle_;
  Server server_;
  std::unique_ptr<GripperServer> gripper_;
  ros::Publisher publisher_;
  ros::WallTimer timer_;
  std::mutex mutex_;
  bool active_ = false;
  trajectory_msgs::JointTrajectory trajectory_;
  std::vector<int> columns_;
  ros::WallTime start_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "ros1_test_controller", ros::init_options::NoRosout);
  Options options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--joints") {
      options.joints = split(value);
    } else if (flag == "--initial") {
      for (const std::string& v : split(value)) options.initial.push_back(std::stod(v));
    } else if (flag == "--ns") {
      options.ns = value;
    } else if (flag == "--gripper-ns") {
      options.gripper_ns = value;
    } else if (flag == "--log") {
      options.log = value;
    } else if (flag == "--abort-after") {
      options.abort_after_s = std::stod(value);
    } else if (flag == "--abort-message") {
      options.abort_message = value;
    } else if (flag == "--silent-file") {
      options.silent_file = value;
    } else if (flag == "--lag") {
      options.lag_s = std::stod(value);
    } else if (flag == "--rate") {
      options.rate_hz = std::stod(value);
    } else {
      std::cerr << "ros1_test_controller: unknown option " << flag << "\n";
      return 2;
    }
  }
  if (options.joints.empty()) {
    std::cerr << "ros1_test_controller: --joints is required\n";
    return 2;
  }
  options.initial.resize(options.joints.size(), 0.0);
  Controller controller(options);
  std::cout << "controller ready" << std::endl;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::waitForShutdown();
  return 0;
}
