#pragma once
// The robot server's collision authority (docs/network.md, "Collisions": the server holds
// the workspace and is the collision authority): every trajectory, plan and jog is checked against
// the workspace and the arm itself before the driver sees it, so a client with a stale or missing
// workspace cannot drive the arm into the table.
//
//   trajectories and plans: any contact along the path (geometry/trajectory_collision.hpp,
//     continuous) is refused: "trajectory collides: at t=1.23 s link 'link5' touches
//     'table_top' (depth 4.2 mm)".
//   the graspable object: not an obstacle (the fingers close on it at the grasp on purpose);
//     where a command's gripper closes on it, it is carried from there to where the gripper
//     opens and checked against the scene and the arm, as the session's validation does (the
//     one implementation, geometry/carried_objects.hpp): "... the carried 'box' touches
//     'table_top' ...", resting contacts up to 1 mm where it is picked or placed excepted.
//     The guard picks it where the workspace file puts it: it does not follow where the
//     arm has put it since (a box placed elsewhere and picked again is not seen carried).
//   jogs: a contact, or a path that brings a link closer to a workspace object than the
//     safety margin, is refused, naming the link, the object and the clearance. A jog that
//     starts inside the margin may still move away (its path's clearance never drops below
//     the start's), so an arm that got there is not stuck.
// Because each jog target and its straight path are checked before motion, a series of jogs
// toward an obstacle stops before the margin is crossed.
//
// Threads: the checker caches poses (one per thread), so calls are serialised by a mutex.

#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/collision_checker.hpp"

namespace telear::net {

inline constexpr double kDefaultSafetyMarginM = 0.03;

class MotionCollisionGuard {
 public:
  // `workspace` with its meshes loaded (an empty one: self-collision only); `workspace_yaml`
  // is what GetInfo hands to clients. Errors: the checker could not be built (names why).
  static Result<std::unique_ptr<MotionCollisionGuard>> create(
      const core::RobotDescription& description, const core::Workspace& workspace,
      std::string workspace_yaml, double safety_margin_m,
      geometry::MeshCollision mesh_collision = geometry::MeshCollision::kConvexParts);

  const std::string& workspace_yaml() const { return workspace_yaml_; }
  double safety_margin_m() const { return margin_m_; }

  // A contact anywhere along the trajectory: the error names the time, link, other and depth.
  Status check_trajectory(const core::Trajectory& trajectory, double gripper_fraction);
  // The same for sampled waypoints, along the straight lines between samples (the path the
  // driver interpolates); times are the samples'.
  Status check_samples(const core::RobotModel& model, const core::TimedWaypoints& samples,
                       double gripper_fraction);
  // The straight joint path from q_from to q_to: contacts, and the margin (see above).
  Status check_jog(const core::RobotModel& model, const Eigen::VectorXd& q_from,
                   const Eigen::VectorXd& q_to, double gripper_fraction);

 private:
  MotionCollisionGuard(geometry::CollisionChecker checker, core::Workspace workspace,
                       std::string workspace_yaml, double margin_m);

  std::mutex mutex_;
  geometry::CollisionChecker checker_;  // the static scene: the graspable objects left out
  core::Workspace workspace_;           // all of it: the graspable object is picked from it
  std::string workspace_yaml_;
  double margin_m_ = kDefaultSafetyMarginM;
};

}  // namespace telear::net
