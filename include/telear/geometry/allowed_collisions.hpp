#pragma once
// The allowed-collision matrix: pairs of robot bodies that are never checked against each
// other, each with the reason it was allowed.
//
//   adjacent  the bodies ride on the same chain frame or on consecutive frames (a joint joins
//             them: their shapes meet at the joint by construction);
//   always    they were in contact in every sampled configuration (built into each other: a
//             wrist housing inside the forearm);
//   never     they were in contact in no sampled configuration (the joint limits keep them
//             apart), so checking them is wasted time;
//   constant  their distance was the same in every sampled configuration, to within
//             AllowedCollisionOptions::constant_tolerance_m (0.1 mm): d_max - d_min <= tol
//             over the samples, no sample in contact, neither body a gripper finger (a
//             finger's distance also follows the opening, which the samples hold fixed).
//             The joints between them only turn them about their shapes' axes of symmetry
//             (a flange on a housing coaxial with the joint that turns it): such a pair
//             carries no information, yet would be every check's minimum clearance and hide
//             the one an operator acts on. (The PUMA's wrist housing and flange, 2.0 mm apart
//             up to 93.7 deg of bend, touch beyond it: not constant, still checked.)
//   user      allowed by the robot file's author.
//
// compute_allowed_collisions samples random configurations within the joint limits (fixed
// seed: the same matrix every run) as MoveIt's setup assistant does; `never` relies on the
// sample count, so it is optional (AllowedCollisionOptions::allow_never). `constant` is on by
// default (allow_constant): a pair it allows was measured at every sample, not only seen
// apart. The matrix is stored in the robot file under `allowed_collisions:`
// (docs/collision.md):
//
//   allowed_collisions:
//     - [base_link, shoulder_link, adjacent]
//     - [forearm_link, wrist_2_link, always]

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::geometry {

struct RobotCollisionModel;

enum class AllowedReason { kAdjacent, kAlways, kNever, kConstant, kUser };

const char* to_string(AllowedReason reason);
// "adjacent", "always", "never", "constant", "user"; nullopt for anything else.
std::optional<AllowedReason> allowed_reason_from_string(const std::string& text);

struct AllowedPair {
  std::string a, b;  // body names, a < b
  AllowedReason reason = AllowedReason::kUser;
};

class AllowedCollisionMatrix {
 public:
  // Allows the pair (in either order); a pair allowed twice keeps its first reason.
  void allow(const std::string& a, const std::string& b, AllowedReason reason);
  bool allowed(const std::string& a, const std::string& b) const;
  const std::vector<AllowedPair>& pairs() const { return pairs_; }

  // The YAML list above (without the key), one pair per line.
  std::string to_yaml() const;
  // Parses that list (`source` names it in messages); unknown reasons are refused.
  static Result<AllowedCollisionMatrix> from_yaml(const std::string& text,
                                                  const std::string& source);

 private:
  std::vector<AllowedPair> pairs_;  // sorted by (a, b)
};

struct AllowedCollisionOptions {
  int samples = 2000;  // random configurations
  std::uint64_t seed = 13;
  bool allow_never = false;            // also allow pairs never in contact (MoveIt does)
  bool allow_constant = true;          // also allow pairs at a constant distance (see above)
  double constant_tolerance_m = 1e-4;  // the largest distance range still constant (m)
  double gripper_fraction = 0.5;       // the gripper opening the samples are taken at

  Status validate() const;
};

// Adjacent pairs only (no sampling).
AllowedCollisionMatrix adjacent_collisions(const RobotCollisionModel& robot);

// Adjacent pairs, then pairs in contact in every sample, then (allow_constant) pairs at a
// constant distance in every sample, then (allow_never) pairs in contact in none; a pair keeps
// the first of these reasons that applies.
Result<AllowedCollisionMatrix> compute_allowed_collisions(
    const RobotCollisionModel& robot, const AllowedCollisionOptions& options = {});

}  // namespace telear::geometry
