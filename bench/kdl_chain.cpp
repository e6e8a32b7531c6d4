#include "bench/kdl_chain.hpp"

#include <kdl/joint.hpp>
#include <kdl/segment.hpp>
#include <kdl/tree.hpp>
#ifdef TELEAR_HAVE_KDL_PARSER
#include <kdl_parser/kdl_parser.hpp>
#endif

namespace telear::bench {

Result<KDL::Chain> kdl_chain_from_dh(const core::RobotModel& model) {
  if (!model.dh()) {
    return Error{"robot '" + model.name() +
                 "' has no DH table; the KDL baseline is built from one (e.g. puma560)"};
  }
  const std::vector<core::DhRow>& rows = *model.dh();
  KDL::Chain chain;
  for (int i = 0; i < model.dof(); ++i) {
    if (model.joint(i).type != core::JointType::kRevolute) {
      return Error{"robot '" + model.name() + "': joint " + std::to_string(i + 1) +
                   " is prismatic; the KDL baseline supports revolute DH joints only"};
    }
    const core::DhRow& row = rows[static_cast<size_t>(i)];
    KDL::Frame tip = KDL::Frame::DH(row.a, row.alpha, row.d, 0.0);
    if (i + 1 == model.dof()) tip = tip * to_kdl(model.T_flange_tool());
    chain.addSegment(
        KDL::Segment(model.joint(i).name,
                     KDL::Joint(model.joint(i).name, KDL::Joint::RotZ, 1.0, row.offset), tip));
  }
  return chain;
}

Result<KDL::Chain> kdl_chain_from_urdf(const core::RobotDescription& description) {
  if (description.urdf_text.empty()) {
    return Error{"robot '" + description.name + "' has no URDF (a DH table)"};
  }
#ifndef TELEAR_HAVE_KDL_PARSER
  return Error{"robot '" + description.name +
               "' is a URDF robot: its KDL baseline needs kdl_parser (libkdl-parser-dev), which "
               "this build did not find"};
#else
  KDL::Tree tree;
  if (!kdl_parser::treeFromString(description.urdf_text, tree)) {
    return Error{"kdl_parser could not read the URDF of robot '" + description.name + "' (" +
                 description.urdf_path + ")"};
  }
  KDL::Chain chain;
  if (!tree.getChain(description.root_link, description.tip_link, chain)) {
    return Error{"kdl_parser's tree of '" + description.urdf_path + "' has no chain from '" +
                 description.root_link + "' to '" + description.tip_link + "'"};
  }
  const int joints = static_cast<int>(chain.getNrOfJoints());
  if (joints != description.model->dof()) {
    // Mimic or gripper joints on the chain: KDL would count them as independent joints.
    return Error{"KDL's chain from '" + description.root_link + "' to '" + description.tip_link +
                 "' has " + std::to_string(joints) + " joints, telear's " +
                 std::to_string(description.model->dof())};
  }
  return chain;
#endif
}

KDL::JntArray to_kdl(const Eigen::VectorXd& q) {
  KDL::JntArray out(static_cast<unsigned int>(q.size()));
  out.data = q;
  return out;
}

Eigen::VectorXd from_kdl(const KDL::JntArray& q) {
  return q.data;
}

KDL::Frame to_kdl(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d& R = T.linear();
  const Eigen::Vector3d& p = T.translation();
  return KDL::Frame(KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0),
                                  R(2, 1), R(2, 2)),
                    KDL::Vector(p.x(), p.y(), p.z()));
}

Eigen::Isometry3d from_kdl(const KDL::Frame& F) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = F.M(r, c);
    T.translation()(r) = F.p(r);
  }
  return T;
}

}  // namespace telear::bench
