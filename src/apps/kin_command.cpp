#include "apps/kin_command.hpp"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>

#include "apps/cli_parsing.hpp"
#include "core/angles.hpp"
#include "core/joint_limits.hpp"
#include "core/kinematics.hpp"
#include "core/robot_loader.hpp"

namespace telear::cli {
namespace {

std::string format_row(const Eigen::Isometry3d& T, int row) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "  [%10.6f %10.6f %10.6f %10.6f]", T.matrix()(row, 0),
                T.matrix()(row, 1), T.matrix()(row, 2), T.matrix()(row, 3));
  return buffer;
}

nlohmann::json matrix_json(const Eigen::Isometry3d& T) {
  return to_row_major(T);
}

// Converts degrees to radians for revolute joints when the user asked for degrees.
Eigen::VectorXd joints_from_user(const RobotModel& model, Eigen::VectorXd q, bool degrees) {
  if (!degrees) return q;
  for (int i = 0; i < model.dof(); ++i) {
    if (model.joint(i).type == JointType::kRevolute) q[i] = radians_from_degrees(q[i]);
  }
  return q;
}

void print_pose(const Eigen::Isometry3d& T, std::ostream& out) {
  const Eigen::Vector3d p = T.translation();
  const Eigen::Vector3d rpy = rpy_from_rotation(T.linear());
  char buffer[160];
  std::snprintf(buffer, sizeof buffer,
                "  xyz = (%.4f, %.4f, %.4f) m   rpy = (%.3f, %.3f, %.3f) deg\n", p.x(), p.y(),
                p.z(), degrees_from_radians(rpy.x()), degrees_from_radians(rpy.y()),
                degrees_from_radians(rpy.z()));
  out << buffer;
}

}  // namespace

int run_kin_info(const KinOptions& options, std::ostream& out, std::ostream& err) {
  auto loaded = load_robot(options.robot);
  if (!loaded) {
    err << "telear kin info: " << loaded.error().message << "\n";
    return 2;
  }
  const RobotModel& model = **loaded;
  if (options.json) {
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
    out << j.dump(2) << "\n";
    return 0;
  }
  out << model.name() << ": " << model.dof() << " joints, from " << model.source() << "\n";
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "  %-3s %-14s %-10s %20s %14s %16s\n", "#", "joint", "type",
                "limits", "max vel", "max acc");
  out << buffer;
  for (int i = 0; i < model.dof(); ++i) {
    const Joint& joint = model.joint(i);
    const bool revolute = joint.type == JointType::kRevolute;
    const double scale = revolute ? 180.0 / M_PI : 1000.0;
    const char* unit = revolute ? "deg" : "mm";
    std::snprintf(
        buffer, sizeof buffer, "  %-3d %-14s %-10s %8.1f .. %6.1f %s %8.1f %s/s %8.1f %s/s2\n",
        i + 1, joint.name.c_str(), revolute ? "revolute" : "prismatic", joint.limits.lower * scale,
        joint.limits.upper * scale, unit, joint.limits.max_velocity * scale, unit,
        joint.limits.max_acceleration * scale, unit);
    out << buffer;
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
  return 0;
}

int run_kin_fk(const KinOptions& options, std::ostream& out, std::ostream& err) {
  auto loaded = load_robot(options.robot);
  if (!loaded) {
    err << "telear kin fk: " << loaded.error().message << "\n";
    return 2;
  }
  const RobotModel& model = **loaded;
  Eigen::VectorXd q;
  if (auto named = model.named_configuration(options.q)) {
    q = *named;
  } else {
    auto values = parse_number_list(options.q, "--q", model.dof());
    if (!values) {
      err << "telear kin fk: " << values.error().message << " (robot '" << model.name() << "' has "
          << model.dof() << " joints)\n";
      return 2;
    }
    q = joints_from_user(model, to_vector(*values), options.degrees);
  }
  KinematicsData data(model);
  forward_kinematics(model, data, q);
  if (options.json) {
    nlohmann::json j;
    j["T_base_tool"] = matrix_json(data.T_base_tool);
    j["frames"] = nlohmann::json::array();
    for (const Eigen::Isometry3d& T : data.T_base_link) j["frames"].push_back(matrix_json(T));
    j["q"] = std::vector<double>(q.begin(), q.end());
    j["within_limits"] = within_limits(model, q);
    out << j.dump(2) << "\n";
    return 0;
  }
  out << "T_base_tool:\n";
  for (int r = 0; r < 4; ++r) out << format_row(data.T_base_tool, r) << "\n";
  print_pose(data.T_base_tool, out);
  if (auto v = first_limit_violation(model, q)) {
    out << "warning: " << describe_violation(model, *v) << "\n";
  }
  return 0;
}

int run_kin_demo(const KinOptions& options, std::ostream& out, std::ostream& err) {
  auto loaded = load_robot(options.robot);
  if (!loaded) {
    err << "telear kin demo: " << loaded.error().message << "\n";
    return 2;
  }
  const RobotModel& model = **loaded;
  out << "telear: the geometric model of " << model.name() << " (" << model.dof()
      << " joints) at its named configurations\n";
  KinematicsData data(model);
  Jacobian J;
  for (const NamedConfiguration& c : model.named_configurations()) {
    forward_kinematics(model, data, c.q);
    geometric_jacobian(model, data, JacobianFrame::kBase, J);
    const double manipulability = std::sqrt(std::max(0.0, (J * J.transpose()).determinant()));
    out << c.name << ":\n";
    print_pose(data.T_base_tool, out);
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "  manipulability = %.5f%s\n", manipulability,
                  manipulability < 1e-6 ? "  (singular)" : "");
    out << buffer;
  }
  return 0;
}

}  // namespace telear::cli
