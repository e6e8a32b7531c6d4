#pragma once
// The Orocos KDL baseline of the kinematics benchmarks: the same arm as a telear RobotModel,
// built as a KDL::Chain from the model's standard-DH table, or, for a URDF robot, by KDL's own
// URDF parser (kdl_parser) from the same URDF text, so that the baseline shares no parsing or
// chaining code with telear.
//
// Each DH row i becomes one KDL segment whose joint rotates about z by q_i + offset_i and
// whose tip frame is KDL::Frame::DH(a, alpha, d, 0) = Tz(d) Tx(a) Rx(alpha), so that the
// segment's pose is Rz(q_i + offset_i) Tz(d_i) Tx(a_i) Rx(alpha_i): the same product telear
// computes. The flange-to-tool transform is folded into the last segment's tip, so the chain
// has exactly dof() segments and KDL's "all frames" are telear's link frames 1..n (the last
// one being the tool).
//
// Only the benchmarks link KDL; core never depends on it.

#include <Eigen/Geometry>
#include <kdl/chain.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::bench {

// Fails (with a message) when the model has no DH table or a prismatic joint.
Result<KDL::Chain> kdl_chain_from_dh(const core::RobotModel& model);

// A URDF robot: kdl_parser's tree of description.urdf_text, and its chain from root_link to
// tip_link (fixed joints become segments with a None joint). Fails (with a message) for a DH
// robot (no URDF), a URDF kdl_parser rejects, or a chain whose joint count is not dof().
Result<KDL::Chain> kdl_chain_from_urdf(const core::RobotDescription& description);

KDL::JntArray to_kdl(const Eigen::VectorXd& q);
Eigen::VectorXd from_kdl(const KDL::JntArray& q);
KDL::Frame to_kdl(const Eigen::Isometry3d& T);
Eigen::Isometry3d from_kdl(const KDL::Frame& F);

}  // namespace telear::bench
