#include "apps/kin_command.hpp"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "apps/cli_parsing.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/ik_analytic.hpp"
#include "telear/core/ik_branches.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/rigid_transform.hpp"
#include "telear/core/robot_loader.hpp"

namespace telear::cli {
namespace {

std::string format_row(const Eigen::Isometry3d& T, int row) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "  [%10.6f %10.6f %10.6f %10.6f]", T.matrix()(row, 0),
                T.matrix()(row, 1), T.matrix()(row, 2), T.matrix()(row, 3));
  return buffer;
}

nlohmann::json matrix_json(const Eigen::Isometry3d& T) {
  return core::to_row_major(T);
}

// Converts degrees to radians for revolute joints when the user asked for degrees.
Eigen::VectorXd joints_from_user(const core::RobotModel& model, Eigen::VectorXd q, bool degrees) {
  if (!degrees) return q;
  for (int i = 0; i < model.dof(); ++i) {
    if (model.joint(i).type == core::JointType::kRevolute) q[i] = core::radians_from_degrees(q[i]);
  }
  return q;
}

void print_pose(const Eigen::Isometry3d& T, std::ostream& out) {
  const Eigen::Vector3d p = T.translation();
  const Eigen::Vector3d rpy = core::rpy_from_rotation(T.linear());
  char buffer[160];
  std::snprintf(buffer, sizeof buffer,
                "  xyz = (%.4f, %.4f, %.4f) m   rpy = (%.3f, %.3f, %.3f) deg\n", p.x(), p.y(),
                p.z(), core::degrees_from_radians(rpy.x()), core::degrees_from_radians(rpy.y()),
                core::degrees_from_radians(rpy.z()));
  out << buffer;
}

// Joint vector in the user's units: degrees for revolute joints with --deg.
Eigen::VectorXd joints_to_user(const core::RobotModel& model, Eigen::VectorXd q, bool degrees) {
  if (!degrees) return q;
  for (int i = 0; i < model.dof(); ++i) {
    if (model.joint(i).type == core::JointType::kRevolute) q[i] = core::degrees_from_radians(q[i]);
  }
  return q;
}

// "[  1.00,  -2.50]": fixed width and precision, and no "-0.00" for values that round to 0.
std::string format_joints(const Eigen::VectorXd& q, int width, int precision) {
  std::string text = "[";
  char buffer[32];
  const double zero = 0.5 * std::pow(10.0, -precision);
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    const double value = std::abs(q[i]) < zero ? 0.0 : q[i];
    std::snprintf(buffer, sizeof buffer, "%*.*f", width, precision, value);
    text += (i ? ", " : "") + std::string(buffer);
  }
  return text + "]";
}

// [SECTION] kin ik: the target pose from --T or --pose

// "16 numbers row-major": comma-separated, or separated by blanks when there is no comma.
Result<Eigen::Isometry3d> transform_from_text(const std::string& text) {
  std::string list = text;
  if (list.find(',') == std::string::npos) {
    std::string joined;
    std::istringstream words(text);
    std::string word;
    while (words >> word) joined += (joined.empty() ? "" : ",") + word;
    list = joined;
  }
  auto values = parse_number_list(list, "--T", 16);
  if (!values) return values.error();
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) M(r, c) = (*values)[static_cast<size_t>(4 * r + c)];
  }
  // Printed matrices carry a few digits only: accept small deviations, then re-orthonormalize.
  constexpr double kTolerance = 1e-4;
  if (const std::string problem = core::rigid_transform_problem(M, kTolerance); !problem.empty()) {
    return Error{"--T is not a rigid transform: " + problem};
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond(Eigen::Matrix3d(M.topLeftCorner<3, 3>())).normalized().toRotationMatrix();
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

Result<Eigen::Isometry3d> target_from_options(const KinOptions& options) {
  if (options.T && options.pose) {
    return Error{"give the target as --T or as --pose, not both"};
  }
  if (options.T) return transform_from_text(*options.T);
  if (options.pose) {
    auto values = parse_number_list(*options.pose, "--pose", 6);
    if (!values) {
      return Error{values.error().message + " (x,y,z in m, roll,pitch,yaw in " +
                   (options.degrees ? "deg)" : "rad)")};
    }
    const std::vector<double>& v = *values;
    Eigen::Vector3d rpy(v[3], v[4], v[5]);
    if (options.degrees)
      rpy = rpy.unaryExpr([](double a) { return core::radians_from_degrees(a); });
    return core::pose_from_xyz_rpy(Eigen::Vector3d(v[0], v[1], v[2]), rpy);
  }
  return Error{"needs a target: --T \"16 numbers, row-major\" or --pose x,y,z,roll,pitch,yaw"};
}

// The demo's IK part: the 8 closed-form solutions for the pose of a named configuration,
// the worst round-trip error |FK(IK(T)) - T| and which solution is the configuration itself.
void print_ik_round_trip(const core::RobotModel& model, const core::PumaGeometry& geometry,
                         const core::NamedConfiguration& c, const Eigen::Isometry3d& T,
                         std::ostream& out) {
  const core::AnalyticIkResult r = core::solve_analytic_ik(model, geometry, T);
  if (r.status == core::IkStatus::kUnreachable) {
    out << "  closed-form IK: " << r.message << "\n";
    return;
  }
  out << "  closed-form IK, " << r.solutions.size() << " solutions (deg):\n";
  core::KinematicsData data(model);
  double worst = 0.0;
  std::string itself;
  for (const core::IkSolution& s : r.solutions) {
    core::forward_kinematics(model, data, s.q);
    worst = std::max(worst, (data.T_base_tool.matrix() - T.matrix()).cwiseAbs().maxCoeff());
    // At a wrist singularity only q4 + q6 is determined: compare that sum.
    double distance = 0.0;
    for (int i = 0; i < model.dof(); ++i) {
      double a = s.q[i], b = c.q[i];
      if (s.singular && (i == 3 || i == 5)) {
        a = s.q[3] + s.q[5];
        b = c.q[3] + c.q[5];
      }
      distance = std::max(distance, std::abs(core::wrap_to_pi(a - b)));
    }
    if (itself.empty() && distance < 1e-9) itself = s.config;
    out << "    " << s.config << "  " << format_joints(joints_to_user(model, s.q, true), 8, 2)
        << (s.within_limits ? "" : "  outside limits") << (s.singular ? "  singular" : "") << "\n";
  }
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "  worst round trip |FK(IK(T)) - T| = %.1e; %s is %s%s\n",
                worst, c.name.c_str(), itself.empty() ? "none of them" : "solution ",
                itself.c_str());
  out << buffer;
  if (!r.message.empty()) out << "  note: " << r.message << "\n";
}

}  // namespace

int run_kin_info(const KinOptions& options, std::ostream& out, std::ostream& err) {
  auto loaded = core::load_robot(options.robot_spec());
  if (!loaded) {
    err << "telear kin info: " << loaded.error().message << "\n";
    return 2;
  }
  const core::RobotModel& model = **loaded;
  if (options.json) {
    nlohmann::json j;
    j["name"] = model.name();
    j["dof"] = model.dof();
    for (int i = 0; i < model.dof(); ++i) {
      const core::JointLimits& l = model.joint(i).limits;
      j["joints"].push_back(
          {{"name", model.joint(i).name},
           {"type", model.joint(i).type == core::JointType::kRevolute ? "revolute" : "prismatic"},
           {"lower", l.lower},
           {"upper", l.upper},
           {"max_velocity", l.max_velocity},
           {"max_acceleration", l.max_acceleration}});
    }
    for (const core::NamedConfiguration& c : model.named_configurations()) {
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
    const core::Joint& joint = model.joint(i);
    const bool revolute = joint.type == core::JointType::kRevolute;
    const double scale = revolute ? core::degrees_from_radians(1.0) : 1000.0;
    const char* unit = revolute ? "deg" : "mm";
    std::snprintf(
        buffer, sizeof buffer, "  %-3d %-14s %-10s %8.1f .. %6.1f %s %8.1f %s/s %8.1f %s/s2\n",
        i + 1, joint.name.c_str(), revolute ? "revolute" : "prismatic", joint.limits.lower * scale,
        joint.limits.upper * scale, unit, joint.limits.max_velocity * scale, unit,
        joint.limits.max_acceleration * scale, unit);
    out << buffer;
  }
  out << "named configurations (deg):\n";
  for (const core::NamedConfiguration& c : model.named_configurations()) {
    out << "  " << std::left << std::setw(6) << c.name << "[";
    for (int i = 0; i < c.q.size(); ++i) {
      out << (i ? ", " : "") << std::defaultfloat << std::setprecision(6)
          << core::degrees_from_radians(c.q[i]);
    }
    out << "]";
    if (auto v = core::first_limit_violation(model, c.q))
      out << "  (outside limits: joint " << v->joint + 1 << ")";
    out << "\n";
  }
  return 0;
}

int run_kin_fk(const KinOptions& options, std::ostream& out, std::ostream& err) {
  auto loaded = core::load_robot(options.robot_spec());
  if (!loaded) {
    err << "telear kin fk: " << loaded.error().message << "\n";
    return 2;
  }
  const core::RobotModel& model = **loaded;
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
  core::KinematicsData data(model);
  core::forward_kinematics(model, data, q);
  if (options.json) {
    nlohmann::json j;
    j["T_base_tool"] = matrix_json(data.T_base_tool);
    j["frames"] = nlohmann::json::array();
    for (const Eigen::Isometry3d& T : data.T_base_link) j["frames"].push_back(matrix_json(T));
    j["q"] = std::vector<double>(q.begin(), q.end());
    j["within_limits"] = core::within_limits(model, q);
    out << j.dump(2) << "\n";
    return 0;
  }
  out << "T_base_tool:\n";
  for (int r = 0; r < 4; ++r) out << format_row(data.T_base_tool, r) << "\n";
  print_pose(data.T_base_tool, out);
  if (auto v = core::first_limit_violation(model, q)) {
    out << "warning: " << core::describe_violation(model, *v) << "\n";
  }
  return 0;
}

int run_kin_ik(const KinOptions& options, std::ostream& out, std::ostream& err) {
  const char* who = "telear kin ik: ";
  auto loaded = core::load_robot(options.robot_spec());
  if (!loaded) {
    err << who << loaded.error().message << "\n";
    return 2;
  }
  const core::RobotModel& model = **loaded;
  auto target = target_from_options(options);
  if (!target) {
    err << who << target.error().message << "\n";
    return 2;
  }
  if (Status s = core::check_ik_config(options.config); !s) {
    err << who << "--config: " << s.error().message << "\n";
    return 2;
  }
  const Eigen::Isometry3d& T = *target;
  auto geometry = core::puma_geometry(model);
  core::AnalyticIkResult result;
  if (geometry) {
    result = core::solve_analytic_ik(model, *geometry, T, options.config);
    if (result.status == core::IkStatus::kUnreachable) {
      err << who << result.message << "\n";
      return 1;
    }
  } else {
    if (!options.config.empty()) {
      err << who << "--config selects closed-form solutions, and " << geometry.error().message
          << "\n";
      return 2;
    }
    if (model.dof() == 6) {
      // Every solution branch, found by seeded restarts (core/ik_branches.hpp), listed like
      // the PUMA's eight; those outside the limits are listed and marked.
      auto branches = core::solve_ik_all(model, T);
      if (!branches) {
        err << who << branches.error().message << "\n";
        return 1;
      }
      result.solutions = std::move(branches).value();
    } else {
      // A redundant arm has infinitely many: the one nearest the zero configuration (clamped
      // into the limits), following the null-space preference (core/ik_redundant.hpp).
      auto solution = core::solve_ik_nearest(model, T, Eigen::VectorXd::Zero(model.dof()));
      if (!solution) {
        err << who << solution.error().message << "\n";
        return 1;
      }
      result.solutions.push_back(std::move(solution).value());
    }
    if (result.solutions.empty()) {
      err << who << "no solution found for the pose (unreachable?)\n";
      return 1;
    }
    if (result.solutions.front().singular) {
      result.status = core::IkStatus::kSingular;
      result.message = "near a singularity (smallest Jacobian singular value below 1e-6)";
    }
  }
  const char* method = geometry ? "analytic" : "numeric";
  if (options.json) {
    nlohmann::json j;
    j["robot"] = model.name();
    j["method"] = method;
    j["status"] = result.status == core::IkStatus::kSingular ? "singular" : "ok";
    if (!result.message.empty()) j["message"] = result.message;
    j["units"] = options.degrees ? "deg" : "rad";
    j["solutions"] = nlohmann::json::array();
    for (const core::IkSolution& s : result.solutions) {
      const Eigen::VectorXd q = joints_to_user(model, s.q, options.degrees);
      j["solutions"].push_back({{"config", s.config},
                                {"q", std::vector<double>(q.begin(), q.end())},
                                {"within_limits", s.within_limits},
                                {"singular", s.singular}});
    }
    out << j.dump(2) << "\n";
    return 0;
  }
  out << model.name() << ": " << result.solutions.size()
      << (result.solutions.size() == 1 ? " solution" : " solutions")
      << (geometry ? " (closed form)" : " (numeric)") << " for\n";
  print_pose(T, out);
  out << "joint values in " << (options.degrees ? "deg" : "rad") << ":\n";
  for (const core::IkSolution& s : result.solutions) {
    const Eigen::VectorXd q = joints_to_user(model, s.q, options.degrees);
    out << "  " << std::left << std::setw(8) << s.config
        << format_joints(q, options.degrees ? 9 : 8, options.degrees ? 4 : 5);
    if (const auto joint = core::first_joint_outside_limits_modulo_turns(model, s.q, 1e-9)) {
      out << "  outside limits (joint " << *joint + 1 << ")";
    } else {
      out << "  within limits";
    }
    if (s.singular) out << ", singular";
    out << "\n";
  }
  if (!result.message.empty()) out << "note: " << result.message << "\n";
  return 0;
}

int run_kin_demo(const KinOptions& options, std::ostream& out, std::ostream& err) {
  auto loaded = core::load_robot(options.robot_spec());
  if (!loaded) {
    err << "telear kin demo: " << loaded.error().message << "\n";
    return 2;
  }
  const core::RobotModel& model = **loaded;
  out << "telear: the geometric model of " << model.name() << " (" << model.dof()
      << " joints) at its named configurations, and inverse kinematics back\n";
  core::KinematicsData data(model);
  core::Jacobian J;
  const auto geometry = core::puma_geometry(model);
  for (const core::NamedConfiguration& c : model.named_configurations()) {
    core::forward_kinematics(model, data, c.q);
    core::geometric_jacobian(model, data, core::JacobianFrame::kBase, J);
    const double manipulability = std::sqrt(std::max(0.0, (J * J.transpose()).determinant()));
    out << c.name << ":\n";
    print_pose(data.T_base_tool, out);
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "  manipulability = %.5f%s\n", manipulability,
                  manipulability < 1e-6 ? "  (singular)" : "");
    out << buffer;
    if (geometry) print_ik_round_trip(model, *geometry, c, data.T_base_tool, out);
  }
  if (!geometry) out << "(no closed-form IK: " << geometry.error().message << ")\n";
  return 0;
}

}  // namespace telear::cli
