#include "telear/core/motion_command.hpp"

#include "telear/core/number_format.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/pose.hpp"

namespace telear::core {
namespace {

MotionOutcome reject(const Eigen::VectorXd& q_current, RejectionKind kind, std::string message,
                     int joint = -1, double value = 0.0, double limit = 0.0) {
  MotionOutcome outcome;
  outcome.accepted = false;
  outcome.q = q_current;
  outcome.rejection = {kind, joint, value, limit, std::move(message)};
  return outcome;
}

MotionOutcome invalid(const Eigen::VectorXd& q_current, std::string message) {
  return reject(q_current, RejectionKind::kInvalidInput, std::move(message));
}

std::string vector_text(const Eigen::Vector3d& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%g, %g, %g)", v.x(), v.y(), v.z());
  return buffer;
}

// Why a 4x4 is not a rigid transform, or an empty string when it is one (for the Cartesian
// target's message; rigid_transform.hpp's rigid_transform_problem words it for the CLI).
std::string cartesian_target_problem(const Eigen::Matrix4d& T, double tolerance) {
  if (!T.allFinite()) return "has a non-finite entry";
  if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > tolerance) {
    return "has a bottom row other than (0, 0, 0, 1)";
  }
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double orthonormality =
      (R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthonormality > tolerance) {
    return "has a rotation block that is not orthonormal (|R R^T - I| = " +
           format_number(orthonormality, "%.3g") + ", tolerance " +
           format_number(tolerance, "%.3g") + ")";
  }
  if (R.determinant() < 0.0) return "has a rotation block with determinant -1 (a reflection)";
  return {};
}

// The bound check: the new configuration must lie within every joint's limits.
std::optional<MotionOutcome> bound_check(const RobotModel& model, const Eigen::VectorXd& q_current,
                                         const Eigen::VectorXd& q_new) {
  if (const auto v = first_limit_violation(model, q_new)) {
    return reject(q_current, RejectionKind::kJointLimit, describe_violation(model, *v), v->joint,
                  v->value, v->limit);
  }
  return std::nullopt;
}

// Smallest singular value along the straight joint-space path, reported below the threshold.
// The path is sampled evenly, then each local minimum of the samples is refined by a
// golden-section search between its neighbours, so that a dip between two samples (crossing
// q5 = 0 half-way between them, say) is found rather than stepped over.
std::optional<SingularityWarning> singularity_along(const RobotModel& model, KinematicsData& data,
                                                    const Eigen::VectorXd& q0,
                                                    const Eigen::VectorXd& q1,
                                                    const MotionOptions& options) {
  Eigen::VectorXd q(q0.size());
  auto sigma_at = [&](double f) {
    if (f <= 0.0) {
      q = q0;
    } else if (f >= 1.0) {
      q = q1;
    } else {
      q = q0 + (q1 - q0) * f;
    }
    return jacobian_min_singular_value(model, data, q);
  };
  const int samples = (q0 == q1) ? 1 : std::max(2, options.singularity_samples);
  std::vector<double> sigma(static_cast<size_t>(samples));
  auto fraction = [&](int i) {
    return samples == 1 ? 0.0 : static_cast<double>(i) / (samples - 1);
  };
  double lowest = std::numeric_limits<double>::infinity();
  double where = 0.0;
  for (int i = 0; i < samples; ++i) {
    sigma[static_cast<size_t>(i)] = sigma_at(fraction(i));
    if (sigma[static_cast<size_t>(i)] < lowest) {
      lowest = sigma[static_cast<size_t>(i)];
      where = fraction(i);
    }
  }
  constexpr double kGolden = 0.6180339887498949;
  for (int i = 1; i + 1 < samples; ++i) {
    const size_t k = static_cast<size_t>(i);
    // A local minimum of the samples; plateaus (the whole path at one singularity) are skipped.
    const bool local_minimum = sigma[k] <= sigma[k - 1] && sigma[k] <= sigma[k + 1] &&
                               (sigma[k] < sigma[k - 1] || sigma[k] < sigma[k + 1]);
    if (!local_minimum) continue;
    double a = fraction(i - 1), b = fraction(i + 1);
    double c = b - kGolden * (b - a), d = a + kGolden * (b - a);
    double sc = sigma_at(c), sd = sigma_at(d);
    for (int iteration = 0; iteration < 40; ++iteration) {
      if (sc < sd) {
        b = d;
        d = c;
        sd = sc;
        c = b - kGolden * (b - a);
        sc = sigma_at(c);
      } else {
        a = c;
        c = d;
        sc = sd;
        d = a + kGolden * (b - a);
        sd = sigma_at(d);
      }
    }
    const double f = sc < sd ? c : d;
    const double s = std::min(sc, sd);
    if (s < lowest) {
      lowest = s;
      where = f;
    }
  }
  if (!(lowest < options.singularity_warning_threshold)) return std::nullopt;
  std::string place;
  if (where == 0.0) {
    place = "at the start";
  } else if (where == 1.0) {
    place = "at the end";
  } else {
    place = "at " + format_number(100.0 * where, "%.0f") + "% of the way";
  }
  SingularityWarning warning;
  warning.measure = lowest;
  warning.fraction = where;
  warning.message = "the move passes near a singularity " + place +
                    ": smallest Jacobian singular value " + format_number(lowest, "%.3g") +
                    " (warning below " + format_number(options.singularity_warning_threshold) + ")";
  return warning;
}

MotionOutcome accept(const RobotModel& model, const Eigen::VectorXd& q_current,
                     Eigen::VectorXd q_new, const MotionOptions& options) {
  KinematicsData data(model);
  MotionOutcome outcome;
  outcome.accepted = true;
  outcome.singularity = singularity_along(model, data, q_current, q_new, options);
  outcome.q = std::move(q_new);
  return outcome;
}

MotionOutcome move_to_pose(const RobotModel& model, const Eigen::VectorXd& q_current,
                           const Eigen::Isometry3d& T_target, const MotionOptions& options) {
  if (Status s = check_redundancy_options(model, options.redundancy); !s) {
    return invalid(q_current, s.error().message);
  }
  auto ik = solve_ik_nearest(model, T_target, q_current, options.redundancy);
  if (!ik) {
    return reject(q_current, RejectionKind::kUnreachable, ik.error().message);
  }
  IkSolution& solution = *ik;
  // The bound check, also guarding against an IK branch that returned a value outside.
  if (auto rejected = bound_check(model, q_current, solution.q)) return *rejected;
  KinematicsData data(model);
  forward_kinematics(model, data, solution.q);
  const Vector6d residual = pose_error_in_base(data.T_base_tool, T_target);
  if (!(residual.head<3>().norm() <= options.ik_tolerance &&
        residual.tail<3>().norm() <= options.ik_tolerance)) {
    return reject(q_current, RejectionKind::kUnreachable,
                  "target unreachable: the IK solution misses it by " +
                      format_number(residual.head<3>().norm(), "%.3g") + " m and " +
                      format_number(residual.tail<3>().norm(), "%.3g") + " rad");
  }
  if (options.reject_singular_cartesian) {
    const double sigma = jacobian_min_singular_value(model, data, solution.q);
    if (sigma < options.singular_tolerance) {
      return reject(q_current, RejectionKind::kSingular,
                    "the move would end at a singularity: smallest Jacobian singular value " +
                        format_number(sigma, "%.3g") + " is below the tolerance of " +
                        format_number(options.singular_tolerance),
                    -1, sigma, options.singular_tolerance);
    }
  }
  MotionOutcome outcome = accept(model, q_current, std::move(solution.q), options);
  outcome.ik_config = std::move(solution.config);
  return outcome;
}

struct CommandVisitor {
  const RobotModel& model;
  const Eigen::VectorXd& q_current;
  const MotionOptions& options;

  MotionOutcome operator()(const JointIncrement& c) const {
    if (c.joint < 0 || c.joint >= model.dof()) {
      return reject(q_current, RejectionKind::kJointIndex,
                    "joint index " + std::to_string(c.joint) + " is out of range: " + model.name() +
                        " has " + std::to_string(model.dof()) + " joints (indices 0 to " +
                        std::to_string(model.dof() - 1) + ")",
                    -1, c.joint, model.dof() - 1);
    }
    if (!std::isfinite(c.delta)) {
      return invalid(q_current, "joint increment of joint " + std::to_string(c.joint + 1) + " (" +
                                    model.joint(c.joint).name +
                                    ") is not a finite number: " + format_number(c.delta));
    }
    Eigen::VectorXd q_new = q_current;
    q_new[c.joint] += c.delta;
    if (auto rejected = bound_check(model, q_current, q_new)) return *rejected;
    return accept(model, q_current, std::move(q_new), options);
  }

  MotionOutcome operator()(const JointTarget& c) const {
    if (Status s = check_joint_vector(model, c.q); !s) {
      return invalid(q_current, "joint target: " + s.error().message);
    }
    if (auto rejected = bound_check(model, q_current, c.q)) return *rejected;
    return accept(model, q_current, c.q, options);
  }

  MotionOutcome operator()(const CartesianIncrement& c) const {
    if (!c.dX.allFinite() || !c.dM.allFinite()) {
      return invalid(q_current, std::string("Cartesian increment (") + to_string(c.frame) +
                                    " frame) is not finite: dX = " + vector_text(c.dX) +
                                    ", dM = " + vector_text(c.dM));
    }
    KinematicsData data(model);
    forward_kinematics(model, data, q_current);
    return move_to_pose(model, q_current, incremented_tool_pose(model, data, c), options);
  }

  MotionOutcome operator()(const CartesianTarget& c) const {
    const std::string problem =
        cartesian_target_problem(c.T_base_tool.matrix(), options.rigid_tolerance);
    if (!problem.empty()) return invalid(q_current, "Cartesian target " + problem);
    // Project the rotation onto SO(3) so that IK sees an exact rotation.
    Eigen::Isometry3d T = c.T_base_tool;
    T.linear() = Eigen::Quaterniond(c.T_base_tool.linear()).normalized().toRotationMatrix();
    return move_to_pose(model, q_current, T, options);
  }
};

}  // namespace

CartesianTarget cartesian_target(const Eigen::Vector3d& X, const Eigen::Vector3d& M) {
  CartesianTarget target;
  target.T_base_tool.linear() = rotation_from_vector(M);
  target.T_base_tool.translation() = X;
  return target;
}

Eigen::Isometry3d incremented_tool_pose(const RobotModel& model, const KinematicsData& current,
                                        const CartesianIncrement& c) {
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  step.linear() = rotation_from_vector(c.dM);
  step.translation() = c.dX;
  const Eigen::Isometry3d& T = current.T_base_tool;
  switch (c.frame) {
    case MotionFrame::kBase: {
      Eigen::Isometry3d T_new = T;
      T_new.linear() = step.linear() * T.linear();
      T_new.translation() = T.translation() + c.dX;
      return T_new;
    }
    case MotionFrame::kWrist:
      return current.T_base_link.back() * step * model.T_flange_tool();
    case MotionFrame::kTool:
      return T * step;
  }
  return T;
}

double jacobian_min_singular_value(const RobotModel& model, KinematicsData& data,
                                   const Eigen::VectorXd& q) {
  update_kinematics(model, data, q);
  Jacobian J;
  geometric_jacobian(model, data, JacobianFrame::kBase, J);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
  return svd.singularValues().minCoeff();
}

MotionOutcome apply_motion(const RobotModel& model, const Eigen::VectorXd& q_current,
                           const MotionCommand& command, const MotionOptions& options) {
  if (Status s = check_joint_vector(model, q_current); !s) {
    return invalid(q_current, "current configuration: " + s.error().message);
  }
  return std::visit(CommandVisitor{model, q_current, options}, command);
}

const char* to_string(MotionFrame frame) {
  switch (frame) {
    case MotionFrame::kBase:
      return "BASE";
    case MotionFrame::kWrist:
      return "WRIST";
    case MotionFrame::kTool:
      return "TOOL";
  }
  return "?";
}

const char* to_string(RejectionKind kind) {
  switch (kind) {
    case RejectionKind::kNone:
      return "none";
    case RejectionKind::kInvalidInput:
      return "invalid input";
    case RejectionKind::kJointIndex:
      return "joint index out of range";
    case RejectionKind::kJointLimit:
      return "joint limit";
    case RejectionKind::kUnreachable:
      return "unreachable";
    case RejectionKind::kSingular:
      return "singular";
  }
  return "?";
}

}  // namespace telear::core
