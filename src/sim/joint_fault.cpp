#include "telear/sim/joint_fault.hpp"

#include <cmath>

namespace telear::sim {

const char* to_string(JointFaultKind kind) {
  switch (kind) {
    case JointFaultKind::kStuck:
      return "stuck";
    case JointFaultKind::kLag:
      return "lag";
    case JointFaultKind::kDrift:
      return "drift";
  }
  return "?";
}

JointMotion apply_joint_fault(const JointFault& fault, const JointMotion& measured,
                              const JointMotion& commanded, bool braked, double& drift_offset,
                              double dt) {
  switch (fault.kind) {
    case JointFaultKind::kStuck:
      return {measured.q, 0.0};
    case JointFaultKind::kLag: {
      if (braked) return {measured.q, 0.0};
      const double dq =
          (commanded.q - measured.q) * (1.0 - std::exp(-dt / fault.lag_time_constant));
      return {measured.q + dq, dq / dt};
    }
    case JointFaultKind::kDrift:
      drift_offset += fault.drift_rate * dt;
      return {commanded.q + drift_offset, commanded.qd + fault.drift_rate};
  }
  return commanded;
}

}  // namespace telear::sim
