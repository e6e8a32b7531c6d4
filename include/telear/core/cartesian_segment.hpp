#pragma once
// Cartesian segments: a waypoint marked `cartesian` (JointWaypoint, telear/core/trajectory.hpp)
// is reached with the tool on the straight line from the previous waypoint's tool pose
// (MoveIt's Cartesian path), position along the line and orientation along the shortest arc
// (slerp), both at the same fraction s of the segment. Trajectory::create calls
// expand_cartesian_segments before timing, so the session's preview and the robot server's
// ExecutePlan expand a plan with the same code; the expansion is part of the plan's hash.
// Method, the measured bound on the tool's distance from the line and the refusals:
// docs/trajectory.md, "Cartesian segments".
//
// Expansion of the segment from waypoint A (joints qa) to waypoint B (joints qb):
//
//   1. The line is cut at s = i / 2^k, with the smallest k whose steps are at most
//      kCartesianMaxStepM long and turn the tool by at most kCartesianMaxStepRad. The poses on
//      it come from repeated halving: positions pa + s (pb - pa), orientations as unit
//      quaternions, the midpoint of two being their normalized sum (exactly the slerp
//      midpoint). Only +, -, *, / and sqrt: no sine or arc cosine to differ between libms.
//   2. Walking from qa, each cut's IK solution nearest the previous one (solve_ik_nearest,
//      deterministic for a given seed) is kept when, against the previous point, no joint
//      moves more than kCartesianMaxJointStepRad (kCartesianMaxJointStepM for a prismatic
//      joint) and the straight joint-space chord between the two passes its middle within
//      kCartesianChordToleranceM and kCartesianChordToleranceRad of the line's pose there.
//      Otherwise the step is halved, down to kCartesianMaxHalvings times: a continuous motion
//      passes after a few halvings, a jump (another IK branch, a singularity) never does.
//      Solutions are rounded to multiples of kCartesianJointGrid (2^-30 rad, about 1 nrad) so
//      that a last-bit difference in the IK of two builds does not change the plan.
//   3. The last solution must be qb's configuration (every joint within
//      kCartesianEndTolerance): the line ends at B's tool pose, and it must end in B's joints.
//      B itself closes the segment with its exact q.
//
// The points found (every one but B) become via waypoints marked `expanded`; B's min_duration
// bounds the whole segment and is split evenly over its steps (step_min_duration). A and B
// keep their own flags and values, B its gripper command. Each expanded point's min_duration
// is at least its step's share of a speed ramp from rest at A to rest at B (a trapezoid along
// the path at half the acceleration the joints allow), so that the via-point timing need not
// lengthen the whole chain to fit its many small blends. Trajectory::create then times the whole
// list as any other (linear segments with parabolic blends through the via points).
//
// Refusals name the waypoint, the fraction of the line and the tool's position there, and
// why: out of reach (the IK's reason), a joint that jumps, or a final configuration other
// than B's.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "telear/core/angles.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::core {

// The expansion's constants. They are part of the time parameterization: changing one
// changes plans, hence kTrajectoryAlgorithm (telear/core/plan_hash.hpp).
inline constexpr double kCartesianMaxStepM = 0.005;                             // 5 mm
inline constexpr double kCartesianMaxStepRad = radians_from_degrees(2.0);       // 2 deg
inline constexpr double kCartesianMaxJointStepRad = radians_from_degrees(2.0);  // revolute
inline constexpr double kCartesianMaxJointStepM = 0.005;                        // prismatic
inline constexpr double kCartesianChordToleranceM = 0.0001;                     // 0.1 mm
inline constexpr double kCartesianChordToleranceRad = radians_from_degrees(0.1);
inline constexpr int kCartesianMaxHalvings = 12;  // a 5 mm step down to 1.2 um
inline constexpr double kCartesianJointGrid = 0x1p-30;
inline constexpr double kCartesianEndTolerance = 1e-6;  // rad or m

// One segment: the joint points strictly between qa and qb (B left out) that follow the line
// from qa's tool pose to qb's, at most max_points of them. `index` (>= 1) is B's waypoint
// number, for the messages ("waypoint[3]: the Cartesian segment from waypoint[2] ..."). qa
// and qb must be valid joint vectors within the limits.
Result<std::vector<Eigen::VectorXd>> cartesian_segment_points(const RobotModel& model,
                                                              const Eigen::VectorXd& qa,
                                                              const Eigen::VectorXd& qb,
                                                              std::size_t index,
                                                              std::size_t max_points);

// Whether any waypoint after the first is marked cartesian.
bool has_cartesian_segments(const std::vector<JointWaypoint>& waypoints);

// The lower bound on the time from waypoint k - 1 to waypoint k of an expanded list (what
// Trajectory::create times with): min_duration, except on a Cartesian waypoint that closes an
// expansion, whose min_duration is the whole segment's and is split evenly over its steps, as
// on its expanded points.
double step_min_duration(const std::vector<JointWaypoint>& waypoints, std::size_t k);

// The operator's waypoints: `waypoints` without the points an expansion inserted.
std::vector<JointWaypoint> without_expanded_points(std::vector<JointWaypoint> waypoints);

// The waypoints with every Cartesian segment expanded as above (waypoints marked `expanded`
// on input are dropped first), with the options' scales and maximum of waypoints.
// `waypoints` and `options` must have passed validate_waypoints. Fails with "waypoint[k]: ..."
// when a segment cannot be followed, or when the expansion would exceed
// options.max_waypoints waypoints in all.
Result<std::vector<JointWaypoint>> expand_cartesian_segments(const RobotModel& model,
                                                             std::vector<JointWaypoint> waypoints,
                                                             const TrajectoryOptions& options);

}  // namespace telear::core
