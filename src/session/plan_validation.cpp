#include "telear/session/plan_validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "telear/core/angles.hpp"
#include "telear/core/cartesian_segment.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/number_format.hpp"
#include "telear/geometry/carried_objects.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/session/plan_collision.hpp"

namespace telear::session {
namespace {

// "0.120 rad (6.9 deg)" or "0.0120 m (12.0 mm)".
std::string distance(const core::RobotModel& model, int joint, double value) {
  if (model.joint(joint).type == core::JointType::kRevolute) {
    return core::format_number(value, "%.3f rad") + " (" +
           core::format_number(core::degrees_from_radians(value), "%.1f deg") + ")";
  }
  return core::format_number(value, "%.4f m") + " (" +
         core::format_number(value * 1000.0, "%.1f mm") + ")";
}

std::string tolerance_text(const core::RobotModel& model, int joint, double value) {
  return model.joint(joint).type == core::JointType::kRevolute
             ? core::format_number(value, "%.3f rad")
             : core::format_number(value, "%.4f m");
}

std::string segment_name(int segment) {
  return "the segment waypoint[" + std::to_string(segment) + "] -> waypoint[" +
         std::to_string(segment + 1) + "]";
}

// Contacts along the trajectory are errors, a workspace clearance below the margin a warning;
// each says where (segment and time) and what (link and object).
template <typename Error, typename Warning>
void check_collisions(geometry::CollisionChecker& checker, const core::Trajectory& trajectory,
                      const ValidationOptions& options,
                      std::optional<geometry::TrajectoryCheckReport>& out, const Error& error,
                      const Warning& warning) {
  const double safety_margin_m = options.safety_margin_m;
  if (!(safety_margin_m >= 0.0) || !std::isfinite(safety_margin_m)) {
    error(-1, -1,
          "safety_margin_m must be a finite number >= 0, got " +
              core::format_number(safety_margin_m, "%g"));
    return;
  }
  // With the workspace, the object the gripper carries is checked too (its resting contacts
  // where picked and placed excepted): the same call the robot server's guard makes.
  auto report = options.workspace
                    ? geometry::check_trajectory_carrying(checker, trajectory, *options.workspace,
                                                          options.collision_check)
                    : geometry::check_trajectory(checker, trajectory, options.collision_check);
  if (!report) {
    error(-1, -1, "the plan could not be checked for collisions: " + report.error().message);
    return;
  }
  for (const geometry::PlanCollision& c : report->collisions) {
    error(c.segment, -1,
          segment_name(c.segment) + " collides at t = " + core::format_number(c.time_s, "%.2f") +
              " s: " + c.body + " hits " + (c.self ? "link " : "") + c.other + " (penetration " +
              core::format_number(c.depth_m * 1e3, "%.1f") + " mm)");
  }
  const geometry::PlanClearance& m = report->min_workspace_clearance;
  if (report->collision_free() && m.distance_m < safety_margin_m) {
    warning(m.segment, -1,
            segment_name(m.segment) + " passes " + core::format_number(m.distance_m * 1e3, "%.1f") +
                " mm from " + m.other + " (" + m.body + ") at t = " +
                core::format_number(m.time_s, "%.2f") + " s, within the safety margin of " +
                core::format_number(safety_margin_m * 1e3, "%.0f") + " mm");
  }
  out = std::move(*report);
}

}  // namespace

const char* to_string(IssueSeverity severity) {
  return severity == IssueSeverity::kError ? "error" : "warning";
}

int ValidationReport::error_count() const {
  return static_cast<int>(std::count_if(issues.begin(), issues.end(), [](const auto& i) {
    return i.severity == IssueSeverity::kError;
  }));
}

int ValidationReport::warning_count() const {
  return static_cast<int>(issues.size()) - error_count();
}

std::string ValidationReport::summary() const {
  const int errors = error_count(), warnings = warning_count();
  std::string text;
  if (errors == 0) {
    text = "ok";
    if (warnings > 0) text += ", ";
  } else {
    text = std::to_string(errors) + (errors == 1 ? " error" : " errors");
    if (warnings > 0) text += ", ";
  }
  if (warnings > 0) text += std::to_string(warnings) + (warnings == 1 ? " warning" : " warnings");
  if (issues.empty()) return text;
  text += ":";
  for (const ValidationIssue& issue : issues) {
    text += std::string("\n  ") + to_string(issue.severity) + ": " + issue.message;
  }
  return text;
}

ValidationReport validate_plan(const Plan& plan, const std::optional<Eigen::VectorXd>& q_real,
                               const ValidationOptions& options) {
  const core::RobotModel& model = plan.model();
  std::vector<ValidationIssue> errors, warnings;
  auto error = [&](int waypoint, int joint, std::string message) {
    errors.push_back({IssueSeverity::kError, waypoint, joint, std::move(message)});
  };
  auto warning = [&](int waypoint, int joint, std::string message) {
    warnings.push_back({IssueSeverity::kWarning, waypoint, joint, std::move(message)});
  };
  std::optional<geometry::TrajectoryCheckReport> collision;
  auto finish = [&]() {
    ValidationReport report;
    report.collision = std::move(collision);
    report.issues = std::move(errors);
    report.issues.insert(report.issues.end(), warnings.begin(), warnings.end());
    return report;
  };

  if (plan.empty()) {
    error(-1, -1, "the plan is empty; add at least one waypoint (the ghost's pose)");
    return finish();
  }
  const auto& waypoints = plan.waypoints();
  bool waypoints_valid = true;
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const std::string name = "waypoint[" + std::to_string(i) + "]";
    if (Status s = plan.check_waypoint(waypoints[i], name); !s) {
      int joint = -1;
      if (waypoints[i].q.size() == model.dof()) {
        if (const auto v = core::first_limit_violation(model, waypoints[i].q)) joint = v->joint;
      }
      error(static_cast<int>(i), joint, s.error().message);
      waypoints_valid = false;
    }
  }
  if (waypoints.size() == 1) {
    warning(0, -1, "the plan has a single waypoint: executing it moves nothing");
  }

  if (!q_real) {
    warning(0, -1, "the real robot's state is unknown: the plan's start was not checked");
  } else if (Status s = core::check_joint_vector(model, *q_real); !s) {
    error(0, -1, "the real robot's reported state is invalid: " + s.error().message);
  } else if (waypoints.front().q.size() == model.dof()) {
    const Eigen::VectorXd gap = (waypoints.front().q - *q_real).cwiseAbs();
    Eigen::Index worst = 0;
    const double largest = gap.maxCoeff(&worst);
    const int j = static_cast<int>(worst);
    if (!(largest <= options.start_tolerance)) {
      error(0, j,
            "the plan starts " + distance(model, j, largest) + " from the real robot at joint " +
                std::to_string(j + 1) + " (" + model.joint(j).name + "; tolerance " +
                tolerance_text(model, j, options.start_tolerance) +
                "); move the robot to the plan's start or reset the ghost");
    }
  }

  if (!waypoints_valid) return finish();

  // Cartesian segments: every one the arm cannot follow is an error at its segment, saying
  // where on the line and why (timing would stop at the first). Their joint points are kept
  // for the singularity warnings below.
  std::vector<std::vector<Eigen::VectorXd>> cartesian_points(waypoints.size());
  bool segments_followed = true;
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    if (!waypoints[i].cartesian) continue;
    auto points = core::cartesian_segment_points(
        model, waypoints[i - 1].q, waypoints[i].q, i,
        static_cast<std::size_t>(plan.trajectory_options().max_waypoints));
    if (!points) {
      error(static_cast<int>(i - 1), -1, points.error().message);
      segments_followed = false;
      continue;
    }
    cartesian_points[i] = std::move(*points);
  }
  if (!segments_followed) return finish();

  auto trajectory = plan.trajectory();
  if (!trajectory) {
    error(-1, -1,
          "the plan cannot be timed within the joint limits: " + trajectory.error().message);
    return finish();
  }
  auto sampled = trajectory->sampled(options.sample_rate_hz, options.max_samples);
  if (!sampled) {
    error(-1, -1, "the plan cannot be sent: " + sampled.error().message);
  } else {
    core::TimedWaypointsLimits limits;
    limits.max_samples = options.max_samples;
    if (Status s = core::validate_timed_waypoints(model, *sampled, limits); !s) {
      error(-1, -1, "the robot would refuse the sampled plan: " + s.error().message);
    }
  }

  if (options.collision_checker)
    check_collisions(*options.collision_checker, *trajectory, options, collision, error, warning);

  // Near-singular segments: one warning per segment, at its closest sample.
  core::KinematicsData data(model);
  const int samples = std::max(2, options.singularity_samples);
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const Eigen::VectorXd& q0 = waypoints[i == 0 ? 0 : i - 1].q;
    const Eigen::VectorXd& q1 = waypoints[i].q;
    if (i > 0 && q0 == q1) continue;  // a dwell: checked as its own waypoint already
    double lowest = std::numeric_limits<double>::infinity();
    double where = 0.0;
    if (i > 0 && waypoints[i].cartesian) {
      // The path is the expansion's points (then waypoint i), not the joint-space line.
      const std::vector<Eigen::VectorXd>& path = cartesian_points[i];
      for (std::size_t k = 0; k <= path.size(); ++k) {
        const double sigma =
            core::jacobian_min_singular_value(model, data, k < path.size() ? path[k] : q1);
        if (sigma < lowest) {
          lowest = sigma;
          where = static_cast<double>(k + 1) / static_cast<double>(path.size() + 1);
        }
      }
    } else {
      const int count = (i == 0) ? 1 : samples;
      for (int k = 0; k < count; ++k) {
        const double s = count == 1 ? 1.0 : static_cast<double>(k) / (count - 1);
        const double sigma = core::jacobian_min_singular_value(model, data, q0 + s * (q1 - q0));
        if (sigma < lowest) {
          lowest = sigma;
          where = s;
        }
      }
    }
    if (lowest < options.singularity_warning_threshold) {
      const std::string at = i == 0 ? "waypoint[0]"
                                    : "the segment waypoint[" + std::to_string(i - 1) +
                                          "] -> waypoint[" + std::to_string(i) + "] (at " +
                                          core::format_number(100.0 * where, "%.0f") + " % of it)";
      warning(static_cast<int>(i == 0 ? 0 : i - 1), -1,
              at + " is near a singularity: smallest Jacobian singular value " +
                  core::format_number(lowest, "%.3g") + " (warning below " +
                  core::format_number(options.singularity_warning_threshold, "%g") +
                  "); check that part of the preview");
    }
  }
  return finish();
}

}  // namespace telear::session
