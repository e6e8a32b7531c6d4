#include "telear/lab/capture_start.hpp"

#include <string>

#include "telear/core/trajectory.hpp"
#include "telear/geometry/carried_objects.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/trajectory_collision.hpp"

namespace telear::lab {

Result<Eigen::VectorXd> capture_start_pose(const vision::RegistrationObservations& observations,
                                           const core::RobotDescription& description,
                                           const core::Workspace& workspace,
                                           const Eigen::VectorXd& ready_q) {
  // The server's static scene (a graspable object is checked as carried, not as an obstacle).
  auto checker =
      geometry::make_collision_checker(description, geometry::static_obstacles(workspace));
  if (!checker) return Error{"the capture's start: " + checker.error().message};
  int seen = 0;
  for (const vision::ObservedConfiguration& c : observations.configurations) {
    if (c.left_pixels.empty() || c.right_pixels.empty()) continue;
    ++seen;
    // The check starts at t = 0: a start in contact fails it too.
    auto move = core::Trajectory::create(*description.model, {{c.q}, {ready_q}});
    if (!move) continue;
    auto report = geometry::check_trajectory(*checker, *move);
    if (report && report->collision_free()) return c.q;
  }
  if (seen == 0) {
    return Error{
        "no observed configuration shows the marker to both cameras: nowhere to start "
        "the capture"};
  }
  return Error{"from none of the " + std::to_string(seen) +
               " observed configurations that show the marker to both cameras is the straight "
               "move to the ready pose free of contact: nowhere to start the capture"};
}

}  // namespace telear::lab
