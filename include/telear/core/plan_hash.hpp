#pragma once
// The fingerprint of a timed plan: "the plan is the message" (docs/trajectory.md). The
// operator's session times its waypoints with Trajectory::create and sends the waypoints,
// the options and plan_hash(); the robot server times the same waypoints with the same
// function and executes only when its hash is the client's. Because Trajectory::create is
// bit-for-bit deterministic (telear/core/trajectory.hpp), equal hashes mean the arm will do
// what the operator previewed, sample for sample.
//
// The hash is SHA-256 (telear/core/sha256.hpp), as 64 lowercase hex digits, of these
// canonical bytes (integers unsigned little-endian, reals IEEE-754 binary64 bit patterns
// little-endian, so -0.0 and 0.0 differ):
//
//   u32 length, the algorithm name (kTrajectoryAlgorithm)
//   u32 dof; per joint: f64 velocity limit, f64 acceleration limit (scaled, as used)
//   f64 velocity_scale, f64 acceleration_scale
//   u32 waypoints, as timed (a Cartesian segment's expanded points included); per waypoint:
//       dof x f64 q, u8 flags (1 via as given, 2 cartesian, 4 expanded), f64 min_duration,
//       u8 has_gripper, f64 gripper opening (0 when unset)
//   f64 duration
//   u32 samples M; M x dof x f64: q at t_i = i / 100 s for i = 0 .. floor(100 duration),
//       then at duration when it falls after the last of those (kPlanHashRateHz)
//   u32 gripper events; per event: f64 time, f64 opening
//
// The parameters pin what was asked; the samples pin what the algorithm made of it, so two
// builds that claim the same algorithm but time differently (a compiler that fuses a
// multiply-add, a changed constant) disagree at once instead of moving the arm differently.

#include <string>
#include <string_view>

#include "telear/core/result.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::core {

// The name of Trajectory::create's time parameterization. Change it whenever a change to
// the profile could change a single bit of its samples (and the golden hashes in
// tests/core/plan_hash_test.cpp with it). History: telear-blend-1, joint waypoints;
// telear-blend-2, Cartesian segments (telear/core/cartesian_segment.hpp).
inline constexpr std::string_view kTrajectoryAlgorithm = "telear-blend-2";
inline constexpr double kPlanHashRateHz = 100.0;
// Up to 1000 s at 100 Hz, as for a sampled trajectory (kMaxTimedSamples).
inline constexpr int kMaxPlanHashSamples = kMaxTimedSamples;

// The canonical bytes above. Fails when the trajectory is longer than kMaxPlanHashSamples
// samples at kPlanHashRateHz allow.
Result<std::string> canonical_plan_bytes(const Trajectory& trajectory);

// SHA-256 of canonical_plan_bytes, lowercase hex.
Result<std::string> plan_hash(const Trajectory& trajectory);

}  // namespace telear::core
