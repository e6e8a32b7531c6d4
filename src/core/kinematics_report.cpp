#include "telear/core/kinematics_report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "telear/core/angles.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/joint_values.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/pose.hpp"

namespace telear::core {
namespace {

std::string matrix_rows(const Eigen::Isometry3d& T) {
  std::string text;
  for (int r = 0; r < 4; ++r) {
    text += "  [";
    for (int c = 0; c < 4; ++c) {
      if (c) text += ' ';
      text += format_number(T.matrix()(r, c), "%10.6f");
    }
    text += "]\n";
  }
  return text;
}

// The closed form's solutions at a named configuration's pose (kin demo).
void round_trip_text(const RobotModel& model, const PumaGeometry& geometry,
                     const NamedConfiguration& c, const Eigen::Isometry3d& T, std::ostream& out) {
  const AnalyticIkResult r = solve_analytic_ik(model, geometry, T);
  if (r.status == IkStatus::kUnreachable) {
    out << "  closed-form IK: " << r.message << "\n";
    return;
  }
  out << "  closed-form IK, " << r.solutions.size() << " solutions (deg):\n";
  KinematicsData data(model);
  double worst = 0.0;
  std::string itself;
  for (const IkSolution& s : r.solutions) {
    forward_kinematics(model, data, s.q);
    worst = std::max(worst, (data.T_base_tool.matrix() - T.matrix()).cwiseAbs().maxCoeff());
    // At a wrist singularity only q4 + q6 is determined: compare that sum.
    double distance = 0.0;
    for (int i = 0; i < model.dof(); ++i) {
      double a = s.q[i], b = c.q[i];
      if (s.singular && (i == 3 || i == 5)) {
        a = s.q[3] + s.q[5];
        b = c.q[3] + c.q[5];
      }
      distance = std::max(distance, std::abs(wrap_to_pi(a - b)));
    }
    if (itself.empty() && distance < 1e-9) itself = s.config;
    out << "    " << s.config << "  "
        << format_joint_values(joint_values_to_degrees(model, s.q), 8, 2)
        << (s.within_limits ? "" : "  outside limits") << (s.singular ? "  singular" : "") << "\n";
  }
  out << "  worst round trip |FK(IK(T)) - T| = " << format_number(worst, "%.1e") << "; " << c.name
      << " is " << (itself.empty() ? "none of them" : "solution ") << itself << "\n";
  if (!r.message.empty()) out << "  note: " << r.message << "\n";
}

}  // namespace

std::string pose_line(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d p = T.translation();
  const Eigen::Vector3d rpy = rpy_from_rotation(T.linear());
  return "  xyz = (" + format_fixed(p.x(), 4) + ", " + format_fixed(p.y(), 4) + ", " +
         format_fixed(p.z(), 4) + ") m   rpy = (" + format_fixed(degrees_from_radians(rpy.x()), 3) +
         ", " + format_fixed(degrees_from_radians(rpy.y()), 3) + ", " +
         format_fixed(degrees_from_radians(rpy.z()), 3) + ") deg\n";
}

std::string robot_info_text(const RobotModel& model) {
  std::ostringstream out;
  out << model.name() << ": " << model.dof() << " joints, from " << model.source() << "\n";
  out << "  " << std::left << std::setw(3) << "#"
      << " " << std::setw(14) << "joint"
      << " " << std::setw(10) << "type"
      << " " << std::right << std::setw(20) << "limits"
      << " " << std::setw(14) << "max vel"
      << " " << std::setw(16) << "max acc"
      << "\n";
  for (int i = 0; i < model.dof(); ++i) {
    const Joint& joint = model.joint(i);
    const bool revolute = joint.type == JointType::kRevolute;
    const double scale = revolute ? degrees_from_radians(1.0) : 1000.0;
    const std::string unit = revolute ? "deg" : "mm";
    out << "  " << std::left << std::setw(3) << i + 1 << " " << std::setw(14) << joint.name << " "
        << std::setw(10) << (revolute ? "revolute" : "prismatic") << std::right << " "
        << format_number(joint.limits.lower * scale, "%8.1f") << " .. "
        << format_number(joint.limits.upper * scale, "%6.1f") << " " << unit << " "
        << format_number(joint.limits.max_velocity * scale, "%8.1f") << " " << unit << "/s "
        << format_number(joint.limits.max_acceleration * scale, "%8.1f") << " " << unit << "/s2\n";
  }
  out << "named configurations (deg):\n";
  for (const NamedConfiguration& c : model.named_configurations()) {
    out << "  " << std::left << std::setw(6) << c.name << "[";
    for (int i = 0; i < c.q.size(); ++i) {
      out << (i ? ", " : "") << std::defaultfloat << std::setprecision(6)
          << degrees_from_radians(c.q[i]);
    }
    out << "]";
    if (auto v = first_limit_violation(model, c.q))
      out << "  (outside limits: joint " << v->joint + 1 << ")";
    out << "\n";
  }
  return out.str();
}

std::string robot_info_json(const RobotModel& model) {
  nlohmann::json j;
  j["name"] = model.name();
  j["dof"] = model.dof();
  for (int i = 0; i < model.dof(); ++i) {
    const JointLimits& l = model.joint(i).limits;
    j["joints"].push_back(
        {{"name", model.joint(i).name},
         {"type", model.joint(i).type == JointType::kRevolute ? "revolute" : "prismatic"},
         {"lower", l.lower},
         {"upper", l.upper},
         {"max_velocity", l.max_velocity},
         {"max_acceleration", l.max_acceleration}});
  }
  for (const NamedConfiguration& c : model.named_configurations()) {
    j["named_configurations"][c.name] = std::vector<double>(c.q.begin(), c.q.end());
  }
  return j.dump(2) + "\n";
}

std::string forward_kinematics_text(const RobotModel& model, const Eigen::VectorXd& q) {
  KinematicsData data(model);
  forward_kinematics(model, data, q);
  std::string text = "T_base_tool:\n";
  text += matrix_rows(data.T_base_tool);
  text += pose_line(data.T_base_tool);
  if (auto v = first_limit_violation(model, q)) {
    text += "warning: " + describe_violation(model, *v) + "\n";
  }
  return text;
}

std::string forward_kinematics_json(const RobotModel& model, const Eigen::VectorXd& q) {
  KinematicsData data(model);
  forward_kinematics(model, data, q);
  nlohmann::json j;
  j["T_base_tool"] = to_row_major(data.T_base_tool);
  j["frames"] = nlohmann::json::array();
  for (const Eigen::Isometry3d& T : data.T_base_link) j["frames"].push_back(to_row_major(T));
  j["q"] = std::vector<double>(q.begin(), q.end());
  j["within_limits"] = within_limits(model, q);
  return j.dump(2) + "\n";
}

std::string ik_listing_text(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                            const IkListing& listing, bool degrees) {
  const AnalyticIkResult& result = listing.result;
  std::ostringstream out;
  out << model.name() << ": " << result.solutions.size()
      << (result.solutions.size() == 1 ? " solution" : " solutions")
      << (listing.closed_form ? " (closed form)" : " (numeric)") << " for\n";
  out << pose_line(T_base_tool);
  out << "joint values in " << (degrees ? "deg" : "rad") << ":\n";
  for (const IkSolution& s : result.solutions) {
    const Eigen::VectorXd q = degrees ? joint_values_to_degrees(model, s.q) : s.q;
    out << "  " << std::left << std::setw(8) << s.config
        << format_joint_values(q, degrees ? 9 : 8, degrees ? 4 : 5);
    if (const auto joint = first_joint_outside_limits_modulo_turns(model, s.q, 1e-9)) {
      out << "  outside limits (joint " << *joint + 1 << ")";
    } else {
      out << "  within limits";
    }
    if (s.singular) out << ", singular";
    out << "\n";
  }
  if (!result.message.empty()) out << "note: " << result.message << "\n";
  return out.str();
}

std::string ik_listing_json(const RobotModel& model, const IkListing& listing, bool degrees) {
  const AnalyticIkResult& result = listing.result;
  nlohmann::json j;
  j["robot"] = model.name();
  j["method"] = listing.closed_form ? "analytic" : "numeric";
  j["status"] = result.status == IkStatus::kSingular ? "singular" : "ok";
  if (!result.message.empty()) j["message"] = result.message;
  j["units"] = degrees ? "deg" : "rad";
  j["solutions"] = nlohmann::json::array();
  for (const IkSolution& s : result.solutions) {
    const Eigen::VectorXd q = degrees ? joint_values_to_degrees(model, s.q) : s.q;
    j["solutions"].push_back({{"config", s.config},
                              {"q", std::vector<double>(q.begin(), q.end())},
                              {"within_limits", s.within_limits},
                              {"singular", s.singular}});
  }
  return j.dump(2) + "\n";
}

std::string kinematics_tour_text(const RobotModel& model) {
  std::ostringstream out;
  out << "telear: the geometric model of " << model.name() << " (" << model.dof()
      << " joints) at its named configurations, and inverse kinematics back\n";
  KinematicsData data(model);
  Jacobian J;
  const auto geometry = puma_geometry(model);
  for (const NamedConfiguration& c : model.named_configurations()) {
    forward_kinematics(model, data, c.q);
    geometric_jacobian(model, data, JacobianFrame::kBase, J);
    const double manipulability = std::sqrt(std::max(0.0, (J * J.transpose()).determinant()));
    out << c.name << ":\n" << pose_line(data.T_base_tool);
    out << "  manipulability = " << format_fixed(manipulability, 5)
        << (manipulability < 1e-6 ? "  (singular)" : "") << "\n";
    if (geometry) round_trip_text(model, *geometry, c, data.T_base_tool, out);
  }
  if (!geometry) out << "(no closed-form IK: " << geometry.error().message << ")\n";
  return out.str();
}

}  // namespace telear::core
