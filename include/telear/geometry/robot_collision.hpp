#pragma once
// The robot as rigid collision bodies riding on its chain frames, posed by forward kinematics.
//
// Bodies: a URDF robot's links with collision geometry (collision_geometry_for: <collision>
// shapes, else its visuals), one body per link; a DH robot (the PUMA) has no URDF links, so
// its body file's primitives stand in (core::body_description_for): a cylinder stays a
// cylinder, a tapered prism becomes the box that holds it (wide and high as its larger end),
// the palm and each finger of the box gripper a box. Names: URDF link names; "link0".."linkN",
// "finger_left", "finger_right" for a DH robot.
//
// Pose of body b riding on chain frame k at configuration q and gripper fraction f:
//   T_base_body = T_base_link[k](q) * T_frame_body(f)
// where T_frame_body is fixed for a rigid body and follows the gripper for a finger (the URDF's
// gripper joints, or the box gripper's opening f * max_opening).
//
// Motion bound (what continuous checking needs). For a straight joint-space motion dq, every
// point p of body b moves at most
//   |dp| <= sum_j |dq_j| * lever(j, b)
// where, for a revolute joint j at or before frame k, lever(j, b) bounds the distance of any
// point of the body from joint j's axis whatever the configuration: the origin offsets met
// from joint j's axis out to frame k (|after_i.t| for i = j..k, |before_i.t| for i = j+1..k:
// the origin of frame i is before_i.t + R * after_i.t from frame i-1's) plus the body's radius
// about frame k's origin; a prismatic joint moves every outboard point by |dq_j| (lever 1),
// and a prismatic joint between j and k adds its largest extension. Joints after frame k do
// not move the body (lever 0).

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/robot_geometry.hpp"

namespace telear::geometry {

struct CollisionBody {
  std::string name;
  int frame = 0;  // chain frame 0..n it rides on
  // How T_frame_body follows the gripper: not at all, through URDF attachment steps, or as a
  // finger of the DH body's box gripper (side -1 / +1).
  enum class Motion { kRigid, kSteps, kBoxFinger };
  Motion motion = Motion::kRigid;
  Eigen::Isometry3d T_frame_body = Eigen::Isometry3d::Identity();  // kRigid
  std::vector<core::AttachmentStep> steps;                         // kSteps
  int finger_side = 0;                                             // kBoxFinger
  std::vector<CollisionShape> shapes;                              // in the body's frame
  // Radius of a sphere about frame `frame`'s origin that holds the body at every gripper
  // opening (m).
  double radius_about_frame_m = 0.0;
};

struct RobotCollisionModel {
  core::RobotModelPtr model;
  std::vector<CollisionBody> bodies;
  std::optional<core::Gripper> gripper;          // URDF gripper joints (kSteps bodies)
  std::optional<core::GripperSpec> box_gripper;  // DH body's gripper (kBoxFinger bodies)
  std::vector<std::string> warnings;             // stand-ins for missing meshes
  // lever[j][b]: the motion bound of body b per unit motion of joint j (see the header).
  std::vector<std::vector<double>> lever;

  int body_index(const std::string& name) const;  // -1 when none
  // T_frame_body at gripper fraction f in [0, 1].
  Eigen::Isometry3d T_frame_body(std::size_t body, double gripper_fraction) const;
  // Adds a body on the tip (frame n, T_frame_body = T_flange_tool * T_tool_body): an object
  // held in the gripper moves with it. Returns its index.
  std::size_t attach(std::string name, std::vector<CollisionShape> shapes,
                     const Eigen::Isometry3d& T_tool_body);
};

// The bounding radius of one shape about its frame's origin after T_link_shape (m).
double shape_radius_about_origin(const CollisionShape& shape);

// Sets every body's radius_about_frame_m and the levers from the bodies as they are (after
// bodies were added, split or their shapes replaced).
void update_motion_bounds(RobotCollisionModel& robot);

// Builds the bodies and their levers. Errors: collision_geometry_for's (meshes), the body
// file's for a DH robot.
Result<RobotCollisionModel> robot_collision_model(const core::RobotDescription& description,
                                                  const GeometryOptions& options = {});

}  // namespace telear::geometry
