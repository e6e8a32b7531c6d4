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
//   user      allowed by the robot file's author.
//
// compute_allowed_collisions samples random configurations within the joint limits (fixed
// seed: the same matrix every run) as MoveIt's setup assistant does; `never` relies on the
// sample count, so it is optional (AllowedCollisionOptions::allow_never). The matrix is
// stored in the robot file under `allowed_collisions:` (docs/collision.md):
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

enum class AllowedReason { kAdjacent, kAlways, kNever, kUser };

const char* to_string(AllowedReason reason);
// "adjacent", "always", "never", "user"; nullopt for anything else.
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
  bool allow_never = false;       // also allow pairs never in contact (MoveIt does)
  double gripper_fraction = 0.5;  // the gripper opening the samples are taken at

  Status validate() const;
};

// Adjacent pairs only (no sampling).
AllowedCollisionMatrix adjacent_collisions(const RobotCollisionModel& robot);

// Adjacent pairs, then pairs in contact in every sample (and, with allow_never, in none).
Result<AllowedCollisionMatrix> compute_allowed_collisions(
    const RobotCollisionModel& robot, const AllowedCollisionOptions& options = {});

}  // namespace telear::geometry
