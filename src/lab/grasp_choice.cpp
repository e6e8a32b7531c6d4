#include "telear/lab/grasp_choice.hpp"

#include <algorithm>
#include <cmath>

#include "telear/core/angles.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/number_format.hpp"

namespace telear::lab {
namespace {

struct Candidate {
  double score = 0.0;
  int tilt_deg = 0;
  int away_deg = 0;
  Eigen::Matrix3d R;
};

std::vector<Candidate> candidates_by_score(const Eigen::Vector3d& to_camera) {
  Eigen::Matrix3d down;
  down.col(0) = Eigen::Vector3d::UnitX();
  down.col(1) = -Eigen::Vector3d::UnitY();
  down.col(2) = -Eigen::Vector3d::UnitZ();
  const auto rad = [](int deg) { return core::radians_from_degrees(deg); };
  std::vector<Candidate> candidates;
  for (int tilt = 0; tilt <= 60; tilt += 10) {
    for (int heading = 0; heading < 360; heading += (tilt == 0 ? 360 : 30)) {
      for (int spin = 0; spin < 360; spin += 30) {
        const Eigen::Matrix3d R =
            (Eigen::AngleAxisd(rad(heading), Eigen::Vector3d::UnitZ()) *
             Eigen::AngleAxisd(rad(tilt), Eigen::Vector3d::UnitY()))
                .toRotationMatrix() *
            down * Eigen::AngleAxisd(rad(spin), Eigen::Vector3d::UnitZ()).toRotationMatrix();
        const double away_deg =
            core::degrees_from_radians(std::acos(std::clamp(R.col(0).dot(to_camera), -1.0, 1.0)));
        candidates.push_back({tilt + away_deg, tilt, static_cast<int>(std::lround(away_deg)), R});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  return candidates;
}

}  // namespace

Eigen::Isometry3d GraspChoice::T_base_tool(const core::RobotModel& model,
                                           const Eigen::Vector3d& grip_in_link_m,
                                           const Eigen::Vector3d& grip_position_base_m) const {
  Eigen::Isometry3d T_base_link = Eigen::Isometry3d::Identity();
  T_base_link.linear() = R_base_link;
  T_base_link.translation() = grip_position_base_m - R_base_link * grip_in_link_m;
  return T_base_link * model.T_flange_tool();
}

std::string GraspChoice::note() const {
  return "gripper tilted " + std::to_string(tilt_deg) + " deg, its marker " +
         std::to_string(away_deg) + " deg away from facing the cameras";
}

Result<GraspChoice> choose_grasp(const core::RobotModel& model, const GraspRequest& request) {
  if (request.grip_positions_base_m.empty()) {
    return Error{"choose_grasp: no task positions for " + request.object_name +
                 "; give at least one"};
  }
  if (request.q_start.size() != model.dof()) {
    return Error{"choose_grasp: q_start has " + std::to_string(request.q_start.size()) +
                 " joints, the robot " + std::to_string(model.dof())};
  }
  const Eigen::Vector3d& first = request.grip_positions_base_m.front();
  const Eigen::Vector3d to_camera = (request.camera_base_m - first).normalized();
  const auto where = [](const Eigen::Vector3d& p) {
    // Appended piece by piece: GCC 12 warns (-Wrestrict) on a "literal" + string chain here.
    std::string text = "[";
    text += core::format_number(p.x(), "%.3f");
    text += ", ";
    text += core::format_number(p.y(), "%.3f");
    text += ", ";
    text += core::format_number(p.z(), "%.3f");
    text += "] m (base frame)";
    return text;
  };
  std::string first_contact;  // of the best candidate that reached every position
  for (const Candidate& c : candidates_by_score(to_camera)) {
    GraspChoice choice{c.R, c.tilt_deg, c.away_deg};
    Eigen::VectorXd q = request.q_start;
    bool reached = true;
    std::string touched;  // this candidate's first contact
    for (const Eigen::Vector3d& p : request.grip_positions_base_m) {
      auto solution =
          core::solve_ik_nearest(model, choice.T_base_tool(model, request.grip_in_link_m, p), q);
      if (!solution) {
        reached = false;
        break;
      }
      q = solution->q;
      if (touched.empty() && request.contact) {
        if (const std::optional<std::string> contact = request.contact(q)) {
          touched = "tilted " + std::to_string(c.tilt_deg) + " deg, the gripper at " + where(p) +
                    ": " + *contact;
        }
      }
    }
    if (reached && touched.empty()) return choice;
    if (reached && first_contact.empty()) first_contact = touched;
  }
  if (!first_contact.empty()) {
    return Error{"choose_grasp: every gripper orientation that reaches " + request.object_name +
                 " at " + where(first) + " within the joint limits touches the scene on the way (" +
                 first_contact + "); move it where the arm reaches it clear of the scene"};
  }
  return Error{"choose_grasp: no gripper orientation reaches " + request.object_name + " at " +
               where(first) + " within the joint limits; move it closer to the robot"};
}

}  // namespace telear::lab
