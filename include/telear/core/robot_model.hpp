#pragma once
// The geometric model of a serial arm: an immutable description shared by every thread
// (Pinocchio's model / data split). Per-thread mutable state lives in KinematicsData.
//
// Every joint i, whatever file it came from, is stored in one canonical form:
//
//   T_{i-1,i}(q_i) = before_i * Z(q_i + offset_i) * after_i
//
// where Z is a rotation about z (revolute) or a translation along z (prismatic). A standard
// Denavit-Hartenberg row has before = I and after = Tz(d) Tx(a) Rx(alpha); a URDF joint has
// before = origin * R_align and after = R_align^T, where R_align turns z onto the joint axis.
// Frame i (the frame link i's body is attached to) is T_base_link[i] = prod_{k<=i} T_{k-1,k}.
// The tool centre point is T_base_tool = T_base_link[n] * T_flange_tool.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::core {

enum class JointType { kRevolute, kPrismatic };

struct JointLimits {
  double lower = 0.0;             // rad or m
  double upper = 0.0;             // rad or m
  double max_velocity = 0.0;      // rad/s or m/s
  double max_acceleration = 0.0;  // rad/s^2 or m/s^2
};

// One row of a standard Denavit-Hartenberg table (Craig's "distal" convention as used by the
// Robotics Toolbox's DHRobot): T = Rz(theta + offset) Tz(d) Tx(a) Rx(alpha).
struct DhRow {
  double d = 0.0;       // m
  double a = 0.0;       // m
  double alpha = 0.0;   // rad
  double offset = 0.0;  // rad, added to the joint variable
};

// How forward kinematics applies a joint, classified once by RobotModel::create so that the
// per-call code takes the cheapest exact product. The kDh* forms are revolute joints with
// before = I and after exactly of the form Tz(d) Tx(a) Rx(alpha) (a standard-DH row, whatever
// file it came from); the twist forms are alpha = 0 and alpha = +-pi/2, where the double
// nearest pi/2 (whose cosine is 6.1e-17, not 0) counts as an exact quarter turn.
enum class JointForm : std::uint8_t {
  kGeneral,         // before * Z(q + offset) * after as full products
  kDh,              // any other twist: cos / sin alpha read from `after`
  kDhTwist0,        // alpha = 0
  kDhTwistPlus90,   // alpha = +pi/2
  kDhTwistMinus90,  // alpha = -pi/2
};

struct Joint {
  std::string name;
  JointType type = JointType::kRevolute;
  Eigen::Isometry3d before = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d after = Eigen::Isometry3d::Identity();
  double offset = 0.0;
  JointLimits limits;
  // Set by RobotModel::create so that forward kinematics can skip identity products.
  bool before_is_identity = true;
  bool after_is_identity = true;
  JointForm form = JointForm::kGeneral;  // also set by RobotModel::create
};

struct NamedConfiguration {
  std::string name;
  Eigen::VectorXd q;
};

class RobotModel {
 public:
  struct Description {
    std::string name;
    std::vector<Joint> joints;
    Eigen::Isometry3d T_flange_tool = Eigen::Isometry3d::Identity();
    std::vector<NamedConfiguration> named_configurations;
    std::optional<std::vector<DhRow>> dh;  // set when the model is a standard DH chain
    std::string source;                    // file it was loaded from, for messages
  };

  // Validates the description (at least one joint, finite transforms, lower <= upper,
  // positive velocity and acceleration limits, named configurations of the right size).
  static Result<RobotModel> create(Description description);

  const std::string& name() const { return d_.name; }
  const std::string& source() const { return d_.source; }
  int dof() const { return static_cast<int>(d_.joints.size()); }
  const std::vector<Joint>& joints() const { return d_.joints; }
  const Joint& joint(int i) const { return d_.joints[static_cast<size_t>(i)]; }
  const Eigen::Isometry3d& T_flange_tool() const { return d_.T_flange_tool; }
  const std::optional<std::vector<DhRow>>& dh() const { return d_.dh; }
  const std::vector<NamedConfiguration>& named_configurations() const {
    return d_.named_configurations;
  }
  std::optional<Eigen::VectorXd> named_configuration(const std::string& name) const;

  const Eigen::VectorXd& lower_limits() const { return lower_; }
  const Eigen::VectorXd& upper_limits() const { return upper_; }
  const Eigen::VectorXd& max_velocities() const { return max_velocity_; }
  const Eigen::VectorXd& max_accelerations() const { return max_acceleration_; }

  // A copy of this model with another flange-to-tool transform.
  Result<RobotModel> with_tool(const Eigen::Isometry3d& T_flange_tool) const;

 private:
  explicit RobotModel(Description description);
  Description d_;
  Eigen::VectorXd lower_, upper_, max_velocity_, max_acceleration_;
};

using RobotModelPtr = std::shared_ptr<const RobotModel>;

// Builds the canonical joints of a standard DH table (all revolute unless `types` says so).
std::vector<Joint> joints_from_dh(const std::vector<DhRow>& rows,
                                  const std::vector<std::string>& names,
                                  const std::vector<JointLimits>& limits);

}  // namespace telear::core
