#pragma once
// The ghost's clearance, live: where the ghost is now (jogged, or posed by the preview at its
// current time), how close it comes to the workspace and which of its links are in contact.
// One CollisionChecker::check(q) per change of the ghost's pose (docs/collision.md), so
// jogging costs one check per command, and a paused preview none.
//
// The clearance shown is to the workspace only: the arm's own links pass millimetres from each
// other by design (the PUMA's wrist housings), which would hide the figure the operator needs.
// Contacts are every contact, self-contacts included (a real fault).
//
// Levels: kContact (any contact: the links are drawn red), kWithinMargin (the clearance is
// below the safety margin: amber), kClear.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "telear/geometry/collision_checker.hpp"

namespace telear::session {

struct ClearanceState {
  enum class Level { kUnchecked, kClear, kWithinMargin, kContact };
  Level level = Level::kUnchecked;
  std::vector<geometry::Contact> contacts;
  geometry::Clearance workspace;    // the smallest distance to a workspace object (not in contact)
  std::vector<int> contact_frames;  // chain frames (0..n) of the bodies in contact, sorted
  double safety_margin_m = 0.0;

  // "clearance 42 mm: link3 – table_top", "contact: link6 – table_top (12.0 mm deep)",
  // "no workspace to check against".
  std::string summary() const;
};

class GhostClearance {
 public:
  // `checker` must outlive this object.
  GhostClearance(geometry::CollisionChecker& checker, double safety_margin_m);

  // Checks (q, gripper) unless it is the pose checked last; returns the state.
  const ClearanceState& update(const Eigen::VectorXd& q, double gripper_fraction);
  const ClearanceState& state() const { return state_; }

 private:
  geometry::CollisionChecker* checker_;
  double safety_margin_m_;
  Eigen::VectorXd last_q_;
  double last_gripper_ = -1.0;
  ClearanceState state_;
};

}  // namespace telear::session
