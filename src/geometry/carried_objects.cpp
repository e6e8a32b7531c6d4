#include "telear/geometry/carried_objects.hpp"

#include <algorithm>

#include "telear/core/kinematics.hpp"
#include "telear/geometry/grasp_model.hpp"

namespace telear::geometry {
namespace {

// The gripper's centre between the fingers, as the simulator grasps with it
// (sim::SceneRenderer::T_base_grip): the DH body's gripper centre on its link, else the tool
// centre point (a URDF arm's tip is between its fingers).
Eigen::Isometry3d T_base_grip(const RobotCollisionModel& robot, const core::KinematicsData& kin) {
  if (!robot.box_gripper) return kin.T_base_tool;
  Eigen::Isometry3d T = kin.T_base_link[static_cast<std::size_t>(robot.box_gripper->link)];
  T.translation() = T * robot.box_gripper->centre.cast<double>();
  return T;
}

double max_opening_m(const RobotCollisionModel& robot) {
  if (robot.box_gripper) return robot.box_gripper->max_opening;
  if (robot.gripper) return robot.gripper->max_opening_m;
  return 0.0;
}

bool by_time(const PlanCollision& a, const PlanCollision& b) {
  return a.time_s < b.time_s;
}

}  // namespace

core::Workspace static_obstacles(const core::Workspace& workspace) {
  core::Workspace obstacles = workspace;
  std::erase_if(obstacles.objects, [](const core::WorkspaceObject& o) { return o.graspable; });
  return obstacles;
}

std::vector<CarriedObject> carried_objects(const core::Trajectory& trajectory,
                                           const RobotCollisionModel& robot,
                                           const core::Workspace& workspace,
                                           double initial_gripper_fraction) {
  std::vector<CarriedObject> carried;
  const double max_opening = max_opening_m(robot);
  if (!(max_opening > 0.0) || !workspace.first_graspable()) return carried;
  auto grasp = GraspModel::create(workspace);
  if (!grasp) return carried;
  const std::string name = workspace.first_graspable()->name;
  const core::RobotModel& model = *robot.model;
  core::KinematicsData kin(model);
  double fraction = initial_gripper_fraction;
  const auto& waypoints = trajectory.waypoints();
  for (std::size_t k = 0; k < waypoints.size(); ++k) {
    // The gripper moves on arrival: the object is taken or let go at the waypoint.
    if (waypoints[k].gripper) fraction = std::clamp(*waypoints[k].gripper, 0.0, 1.0);
    core::forward_kinematics(model, kin, waypoints[k].q);
    const bool was_held = grasp->held();
    const Eigen::Isometry3d T_base_object = grasp->T_base_object();
    grasp->update(T_base_grip(robot, kin), fraction * max_opening);
    if (!was_held && grasp->held()) {
      carried.push_back({name, k, waypoints.size() - 1, T_base_object});
    } else if (was_held && !grasp->held()) {
      carried.back().release = k;
    }
  }
  return carried;
}

Result<std::vector<PlanCollision>> check_carried_objects(const core::Trajectory& trajectory,
                                                         const CollisionChecker& checker,
                                                         const core::Workspace& workspace,
                                                         const TrajectoryCheckOptions& options) {
  std::vector<PlanCollision> contacts;
  const std::vector<CarriedObject> carried =
      carried_objects(trajectory, checker.robot(), workspace, options.initial_gripper_fraction);
  const auto& waypoints = trajectory.waypoints();
  const auto& times = trajectory.waypoint_times();
  for (const CarriedObject& c : carried) {
    if (c.release <= c.grasp) continue;  // held at the last waypoint only: it does not move
    // The scene the checker has, and the held object where it is picked up.
    core::Workspace scene;
    scene.name = workspace.name;
    scene.source = workspace.source;
    for (const core::WorkspaceObject& o : workspace.objects) {
      const auto& names = checker.object_names();
      if (std::find(names.begin(), names.end(), o.name) != names.end()) {
        scene.objects.push_back(o);
      } else if (o.name == c.name) {
        scene.objects.push_back(o);
        scene.objects.back().T_base_object = c.T_base_object;
      }
    }
    auto holding = CollisionChecker::create(checker.robot(), scene, checker.allowed());
    if (!holding) return Error{"the carried " + c.name + ": " + holding.error().message};
    double fraction = options.initial_gripper_fraction;
    for (std::size_t k = 0; k <= c.grasp; ++k) {
      if (waypoints[k].gripper) fraction = std::clamp(*waypoints[k].gripper, 0.0, 1.0);
    }
    if (Status s = holding->attach_object(c.name, waypoints[c.grasp].q, fraction); !s) {
      return Error{"the carried " + c.name + ": " + s.error().message};
    }
    // The stretch as a trajectory of its own: the same segments, timed the same (a stop
    // waypoint is at rest), the gripper as it is at the grasp.
    std::vector<core::JointWaypoint> stretch(waypoints.begin() + static_cast<long>(c.grasp),
                                             waypoints.begin() + static_cast<long>(c.release) + 1);
    stretch.front().min_duration = 0.0;
    stretch.front().gripper = fraction;
    core::TrajectoryOptions timing = trajectory.options();
    timing.max_waypoints = std::max(timing.max_waypoints, static_cast<int>(stretch.size()));
    auto sub = core::Trajectory::create(*checker.robot().model, std::move(stretch), timing);
    if (!sub) return Error{"the carried " + c.name + ": " + sub.error().message};
    TrajectoryCheckOptions held_options = options;
    held_options.initial_gripper_fraction = fraction;
    auto report = check_trajectory(*holding, *sub, held_options);
    if (!report) return Error{"the carried " + c.name + ": " + report.error().message};
    const auto& sub_times = sub->waypoint_times();
    for (PlanCollision contact : report->collisions) {
      if (contact.body != c.name && contact.other != c.name) continue;  // the arm's own
      if (contact.depth_m <= kRestingContactDepthM) continue;  // resting where picked or placed
      if (contact.other == c.name) {
        std::swap(contact.body, contact.other);  // the held object first (self: an arm link)
      }
      const auto segment = static_cast<std::size_t>(contact.segment);
      contact.time_s = times[c.grasp + segment] + (contact.time_s - sub_times[segment]);
      contact.segment += static_cast<int>(c.grasp);
      contacts.push_back(std::move(contact));
    }
  }
  std::sort(contacts.begin(), contacts.end(), by_time);
  return contacts;
}

Result<TrajectoryCheckReport> check_trajectory_carrying(CollisionChecker& checker,
                                                        const core::Trajectory& trajectory,
                                                        const core::Workspace& workspace,
                                                        const TrajectoryCheckOptions& options) {
  auto report = check_trajectory(checker, trajectory, options);
  if (!report) return report.error();
  auto held = check_carried_objects(trajectory, checker, workspace, options);
  if (!held) return held.error();
  report->collisions.insert(report->collisions.end(), held->begin(), held->end());
  std::stable_sort(report->collisions.begin(), report->collisions.end(), by_time);
  return report;
}

}  // namespace telear::geometry
