#pragma once
// Fault injection for tests: a joint that no longer does what the servo commands, so that an
// execution monitor (commanded vs measured, or ghost vs video) has something to detect.
//
//   kStuck  the joint stays where it is (velocity 0) whatever it is commanded.
//   kLag    the joint follows its command through a first-order lag of time constant tau:
//           q += (q_cmd - q) (1 - exp(-dt / tau)) per period; it falls behind fast motions.
//   kDrift  the joint creeps away from its command at `drift_rate` (rad/s or m/s), as with a
//           slipping brake: measured q = q_cmd + drift_rate * (time since injection). It keeps
//           creeping while the arm is e-stopped and at rest, and can run into a joint limit,
//           where the robot's hard clamp stops it and latches a fault.
//
// A stuck or lagging joint is held by its brake while the arm is e-stopped.

#include <string>

#include "telear/sim/joint_motion.hpp"

namespace telear::sim {

enum class JointFaultKind { kStuck, kLag, kDrift };

const char* to_string(JointFaultKind kind);

struct JointFault {
  int joint = 0;  // 0-based
  JointFaultKind kind = JointFaultKind::kStuck;
  double lag_time_constant = 0.2;  // s, > 0 (kLag)
  double drift_rate = 0.0;         // rad/s or m/s, finite (kDrift)
};

// One servo period of a faulty joint: its measured state before the period, its commanded
// state after it, and the fault give its measured state after the period. drift_offset is
// the accumulated drift (kDrift), updated here. braked: the arm is e-stopped.
JointMotion apply_joint_fault(const JointFault& fault, const JointMotion& measured,
                              const JointMotion& commanded, bool braked, double& drift_offset,
                              double dt);

}  // namespace telear::sim
