// URDF loading through urdfdom. A URDF joint is
//   T_parent_child(q) = origin * Rot(axis, q)
// and telear's canonical form needs the joint to move about z, so each movable joint becomes
//   before = (fixed joints folded in) * origin * R_align,  after = R_align^T
// with R_align turning z onto the axis; trailing fixed joints (flange, tool0) fold into the
// last joint's `after`, so frame n is the tip link.

#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "telear/core/robot_loader.hpp"

namespace telear::core {
namespace {

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return T;
}

// Defaults for what URDF leaves out: it has no acceleration limit at all, and continuous
// joints often carry no velocity limit. Conservative values; docs/robot-files.md says so.
constexpr double kDefaultVelocity = 1.0;          // rad/s or m/s
constexpr double kAccelerationPerVelocity = 4.0;  // 1/s: full speed in 0.25 s

}  // namespace

Result<RobotModel> parse_urdf(const std::string& text, const std::string& source,
                              const std::string& tip_link) {
  const std::string where = "URDF '" + source + "'";
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(text);
  if (!urdf) return Error{where + ": not a valid URDF (urdfdom could not parse it)"};
  const urdf::LinkConstSharedPtr root = urdf->getRoot();
  if (!root) return Error{where + ": has no root link"};

  urdf::LinkConstSharedPtr tip;
  if (!tip_link.empty()) {
    tip = urdf->getLink(tip_link);
    if (!tip) return Error{where + ": has no link named '" + tip_link + "'"};
  } else {
    std::vector<urdf::LinkSharedPtr> links;
    urdf->getLinks(links);
    std::vector<std::string> leaves;
    for (const auto& link : links) {
      if (link->child_links.empty()) {
        leaves.push_back(link->name);
        tip = link;
      }
    }
    if (leaves.size() != 1) {
      std::string names;
      for (const auto& n : leaves) names += (names.empty() ? "" : ", ") + n;
      return Error{where + ": the tree has several leaf links (" + names +
                   "); name the tip link of the arm"};
    }
  }

  std::vector<urdf::JointConstSharedPtr> path;
  for (urdf::LinkConstSharedPtr link = tip; link && link != root; link = link->getParent()) {
    if (!link->parent_joint) break;
    path.push_back(link->parent_joint);
  }
  std::reverse(path.begin(), path.end());

  RobotModel::Description d;
  d.name = urdf->getName();
  d.source = source;
  Eigen::Isometry3d pending = Eigen::Isometry3d::Identity();
  for (const urdf::JointConstSharedPtr& uj : path) {
    const Eigen::Isometry3d origin = to_isometry(uj->parent_to_joint_origin_transform);
    if (uj->type == urdf::Joint::FIXED) {
      if (d.joints.empty()) {
        pending = pending * origin;
      } else {
        d.joints.back().after = d.joints.back().after * origin;
      }
      continue;
    }
    Joint joint;
    joint.name = uj->name;
    switch (uj->type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        joint.type = JointType::kRevolute;
        break;
      case urdf::Joint::PRISMATIC:
        joint.type = JointType::kPrismatic;
        break;
      default:
        return Error{where + ": joint '" + uj->name +
                     "' is floating or planar; telear handles revolute, continuous, prismatic "
                     "and fixed joints"};
    }
    Eigen::Vector3d axis(uj->axis.x, uj->axis.y, uj->axis.z);
    if (!axis.allFinite() || axis.norm() < 1e-9) {
      return Error{where + ": joint '" + uj->name + "' has a zero or invalid axis"};
    }
    axis.normalize();
    const Eigen::Matrix3d R_align =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
    Eigen::Isometry3d align = Eigen::Isometry3d::Identity();
    align.linear() = R_align;
    joint.before = pending * origin * align;
    joint.after = align.inverse();
    pending = Eigen::Isometry3d::Identity();

    JointLimits& l = joint.limits;
    if (uj->type == urdf::Joint::CONTINUOUS || !uj->limits) {
      l.lower = -std::numeric_limits<double>::infinity();
      l.upper = std::numeric_limits<double>::infinity();
    } else {
      l.lower = uj->limits->lower;
      l.upper = uj->limits->upper;
    }
    l.max_velocity =
        (uj->limits && uj->limits->velocity > 0.0) ? uj->limits->velocity : kDefaultVelocity;
    l.max_acceleration = kAccelerationPerVelocity * l.max_velocity;
    d.joints.push_back(std::move(joint));
  }
  if (d.joints.empty()) {
    return Error{where + ": no movable joint between root '" + root->name + "' and tip '" +
                 tip->name + "'"};
  }
  d.named_configurations.push_back(
      {"zero", Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d.joints.size()))});
  return RobotModel::create(std::move(d));
}

Result<RobotModel> load_urdf_file(const std::string& path, const std::string& tip_link) {
  std::ifstream in(path);
  if (!in) return Error{"cannot open URDF file '" + path + "'"};
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_urdf(buffer.str(), path, tip_link);
}

}  // namespace telear::core
