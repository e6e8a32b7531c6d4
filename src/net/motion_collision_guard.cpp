#include "telear/net/motion_collision_guard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "telear/core/number_format.hpp"
#include "telear/geometry/carried_objects.hpp"
#include "telear/geometry/trajectory_collision.hpp"

namespace telear::net {

namespace {

std::string millimetres(double m) {
  return core::format_number(m * 1e3, "%.1f mm");
}

// The body in contact: an arm link, or the workspace object the gripper carries (its contacts
// name it as the body, geometry/carried_objects.hpp).
std::string body_name(const geometry::PlanCollision& c, const core::Workspace& workspace) {
  const core::WorkspaceObject* held = workspace.first_graspable();
  return (held && c.body == held->name ? "the carried '" : "link '") + c.body + "'";
}

std::string describe(const geometry::PlanCollision& c, double time_s,
                     const core::Workspace& workspace) {
  return "at t=" + core::format_number(time_s, "%.2f s") + " " + body_name(c, workspace) +
         " touches " + (c.self ? "link '" : "'") + c.other + "' (depth " + millimetres(c.depth_m) +
         ")";
}

// A jog may end no closer than this below its start's clearance and still count as moving
// away (the checker samples the path, so a flat minimum reads a hair below the start).
constexpr double kMovingAwayToleranceM = 1e-4;

// The continuous check of `trajectory` from the gripper opening at the command, the object it
// carries included (the caller holds the guard's mutex: the checker caches poses).
Result<geometry::TrajectoryCheckReport> check_path(geometry::CollisionChecker& checker,
                                                   const core::Workspace& workspace,
                                                   const core::Trajectory& trajectory,
                                                   double gripper_fraction) {
  geometry::TrajectoryCheckOptions options;
  options.initial_gripper_fraction = std::clamp(gripper_fraction, 0.0, 1.0);
  auto report = geometry::check_trajectory_carrying(checker, trajectory, workspace, options);
  if (!report) return Error{"collision check failed: " + report.error().message};
  return report;
}

}  // namespace

Result<std::unique_ptr<MotionCollisionGuard>> MotionCollisionGuard::create(
    const core::RobotDescription& description, const core::Workspace& workspace,
    std::string workspace_yaml, double safety_margin_m, geometry::MeshCollision mesh_collision) {
  if (!(safety_margin_m >= 0.0 && std::isfinite(safety_margin_m))) {
    return Error{"safety margin " + core::format_number(safety_margin_m, "%g") +
                 " m must be a finite number >= 0"};
  }
  // The graspable objects are the task's targets, not obstacles: the fingers close on the box
  // at the grasp on purpose. A carried one is checked from its grasp to its release.
  geometry::CollisionSetupOptions setup;
  setup.mesh_collision = mesh_collision;
  auto checker =
      geometry::make_collision_checker(description, geometry::static_obstacles(workspace), setup);
  if (!checker) return Error{"collision checker: " + checker.error().message};
  return std::unique_ptr<MotionCollisionGuard>(new MotionCollisionGuard(
      std::move(checker).value(), workspace, std::move(workspace_yaml), safety_margin_m));
}

MotionCollisionGuard::MotionCollisionGuard(geometry::CollisionChecker checker,
                                           core::Workspace workspace, std::string workspace_yaml,
                                           double margin_m)
    : checker_(std::move(checker)),
      workspace_(std::move(workspace)),
      workspace_yaml_(std::move(workspace_yaml)),
      margin_m_(margin_m) {}

Status MotionCollisionGuard::check_trajectory(const core::Trajectory& trajectory,
                                              double gripper_fraction) {
  std::lock_guard lock(mutex_);
  auto report = check_path(checker_, workspace_, trajectory, gripper_fraction);
  if (!report) return report.error();
  if (!report->collision_free()) {
    const auto& c = report->collisions.front();
    return Error{"trajectory collides: " + describe(c, c.time_s, workspace_)};
  }
  return Status::Ok();
}

Status MotionCollisionGuard::check_samples(const core::RobotModel& model,
                                           const core::TimedWaypoints& samples,
                                           double gripper_fraction) {
  // The samples as stop waypoints: the checked path is the same straight lines between them
  // (the timing differs, so times are mapped back onto the samples' below).
  std::vector<core::JointWaypoint> waypoints;
  waypoints.reserve(samples.q.size() + 1);
  for (std::size_t k = 0; k < samples.q.size(); ++k) {
    const double dt = k == 0 ? 0.0 : samples.times[k] - samples.times[k - 1];
    waypoints.emplace_back(samples.q[k], dt);
  }
  if (waypoints.size() == 1) waypoints.push_back(waypoints.front());  // a single pose
  core::TrajectoryOptions timing;
  timing.max_waypoints = static_cast<int>(waypoints.size()) + 1;
  auto trajectory = core::Trajectory::create(model, std::move(waypoints), timing);
  if (!trajectory) return Error{"collision check failed: " + trajectory.error().message};
  std::lock_guard lock(mutex_);
  auto report = check_path(checker_, workspace_, *trajectory, gripper_fraction);
  if (!report) return report.error();
  if (report->collision_free()) return Status::Ok();
  const auto& c = report->collisions.front();
  double time_s = c.time_s;
  const auto& wt = trajectory->waypoint_times();
  const auto k = static_cast<std::size_t>(c.segment);
  if (k + 1 < wt.size() && k + 1 < samples.times.size() && wt[k + 1] > wt[k]) {
    const double fraction = std::clamp((c.time_s - wt[k]) / (wt[k + 1] - wt[k]), 0.0, 1.0);
    time_s = samples.times[k] + fraction * (samples.times[k + 1] - samples.times[k]);
  } else if (k < samples.times.size()) {
    time_s = samples.times[k];
  }
  return Error{"trajectory collides: " + describe(c, time_s, workspace_)};
}

Status MotionCollisionGuard::check_jog(const core::RobotModel& model, const Eigen::VectorXd& q_from,
                                       const Eigen::VectorXd& q_to, double gripper_fraction) {
  auto trajectory = core::Trajectory::create(model, {{q_from}, {q_to}});
  if (!trajectory) return Error{"collision check failed: " + trajectory.error().message};
  std::lock_guard lock(mutex_);
  auto report = check_path(checker_, workspace_, *trajectory, gripper_fraction);
  if (!report) return report.error();
  if (!report->collision_free()) {
    const auto& c = report->collisions.front();
    return Error{"jog collides: " + body_name(c, workspace_) + " would touch " +
                 (c.self ? "link '" : "'") + c.other + "' (depth " + millimetres(c.depth_m) + ")"};
  }
  const geometry::PlanClearance& path = report->min_workspace_clearance;
  if (path.distance_m >= margin_m_) return Status::Ok();
  // Inside the margin: allowed only when moving away (no closer than where it starts).
  checker_.set_configuration(q_from, std::clamp(gripper_fraction, 0.0, 1.0));
  double start_m = std::numeric_limits<double>::infinity();
  for (const auto& pair : checker_.pairs()) {
    if (pair.other_object >= 0) start_m = std::min(start_m, checker_.distance(pair).distance_m);
  }
  if (path.distance_m >= start_m - kMovingAwayToleranceM) return Status::Ok();
  return Error{"jog refused: link '" + path.body + "' would come within " +
               millimetres(path.distance_m) + " of '" + path.other +
               "', inside the safety margin " + millimetres(margin_m_)};
}

}  // namespace telear::net
