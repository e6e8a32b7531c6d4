#pragma once
// What the ROS 1 and ROS 2 robot drivers share (C++20, no ROS types): the model's joints by
// name, the checks each driver keeps below the server as its own last line of defence, a
// trajectory's samples as a goal's points, and the previewed plan played on the ghost topic.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::drivers {

std::string quoted(const std::string& text);

// The model's joint names in its (the URDF's) order, and as a list for messages.
std::vector<std::string> joint_names(const core::RobotModel& model);
std::string joint_list(const std::vector<std::string>& names);

// `values` (named by `names`, as a JointState or a feedback carries them) in the order of
// `wanted`; nothing, with the first wanted joint that has no value in *missing, when one lacks.
std::optional<Eigen::VectorXd> values_by_name(const std::vector<std::string>& wanted,
                                              const std::vector<std::string>& names,
                                              const std::vector<double>& values,
                                              std::string* missing = nullptr);

// "jog ignored: it expired 0.012 s before it arrived", or later than max_duration_s from now.
Status check_jog_expiry(std::int64_t expires_ns, std::int64_t now_ns, double max_duration_s);

// `what` refused while the e-stop is engaged, a trajectory (running_id) runs, or a fault.
Status check_can_move(const std::string& what, bool estop, const std::string& estop_reason,
                      const std::optional<std::string>& running_id,
                      const std::optional<std::string>& fault);

// A plan's gripper events on an arm whose opening cannot change: those that keep `opening`
// (a plan's waypoints carry it even when it does not change) are no-ops, one that changes it
// is refused (`why_none` says why there is no gripper) rather than run without its grasp.
Status check_gripper_events_keep(const std::string& what,
                                 const std::vector<core::GripperEvent>& events, double opening,
                                 const std::string& why_none);

// A goal's points: positions only, at whole nanoseconds from the first sample (rounded as
// PreviewPlan's answer and ExecuteTrajectory's wire are, so they are exactly the preview's).
struct GoalPoints {
  std::vector<std::int64_t> times_ns;
  std::vector<std::vector<double>> positions;
};
GoalPoints goal_points(const core::TimedWaypoints& samples);

// A jog from q to target: over duration_s (a velocity held until the expiry), or timed by
// core's parameterization at the joints' limits, sampled at rate_hz.
Result<GoalPoints> jog_points(const core::RobotModel& model, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& target, std::optional<double> duration_s,
                              double rate_hz);

// A previewed plan played in real time, a frame at a time (the drivers' ghost topic).
class PreviewPlayback {
 public:
  void start(core::TimedWaypoints samples, std::int64_t now_ns);
  bool playing() const { return playing_; }
  struct Frame {
    Eigen::VectorXd q;                    // the sample due now
    std::optional<std::int64_t> next_ns;  // when the next frame is due; none: it has ended
  };
  // Call while playing().
  Frame advance(std::int64_t now_ns, double rate_hz);

 private:
  core::TimedWaypoints samples_;
  std::int64_t started_ns_ = 0;
  std::size_t next_ = 0;
  bool playing_ = false;
};

}  // namespace telear::drivers
