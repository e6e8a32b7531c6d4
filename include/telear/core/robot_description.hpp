#pragma once
// A robot as a lab describes it: the kinematic chain (RobotModel) plus everything around it
// that the URDF and the robot file say — every URDF link and where it rides on the chain,
// its visual and collision geometry (URIs unresolved: the geometry layer loads meshes), the
// gripper joints and how the opening maps onto them, the marker mount and body override.
//
// Where a URDF link sits: the chain has frames 0..n (frame 0 = the root link, frame i = the
// child link of movable chain joint i, fixed joints folded in; see robot_model.hpp). Every
// other URDF link is attached to the chain frame it hangs from, through fixed joints and
// gripper joints:
//
//   T_frame_link(opening) = steps[0](opening) * steps[1](opening) * ...
//
// where a step is a fixed transform, or a gripper joint in canonical form
// (before * Z(value) * after) whose value follows the gripper opening. Movable joints that are
// neither on the chain nor gripper joints (nor mimic of one) are held at 0 (docs/robot-files.md).
//
// A DH robot has no URDF: its RobotDescription has no links (its body comes from the body
// file, core/arm_body.hpp), and urdf_text is empty.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// One <visual> or <collision> element of a URDF link, in that link's frame.
struct GeometryElement {
  enum class Kind { kBox, kCylinder, kSphere, kMesh };
  Kind kind = Kind::kBox;
  Eigen::Isometry3d T_link_geometry = Eigen::Isometry3d::Identity();  // <origin>
  Eigen::Vector3d box_size = Eigen::Vector3d::Zero();                 // m, full size
  double radius = 0.0;                                                // cylinder, sphere (m)
  double length = 0.0;                                                // cylinder (m), along z
  std::string mesh_uri;                             // as written: package://, file://, relative
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  // mesh
  std::optional<Eigen::Vector4f> rgba;              // URDF material colour (0..1), if any
  std::string material_name;
};

// One step from a chain frame towards a link (see the header comment).
struct AttachmentStep {
  Eigen::Isometry3d fixed = Eigen::Isometry3d::Identity();  // used when gripper_joint < 0
  int gripper_joint = -1;  // index into Gripper::joints, or -1 for a fixed step
};

struct RobotLink {
  std::string name;
  int frame = 0;                      // chain frame 0..n this link rides on
  std::vector<AttachmentStep> steps;  // frame -> link; empty: the link IS the frame
  std::vector<GeometryElement> visuals;
  std::vector<GeometryElement> collisions;
  bool moves_with_gripper() const;  // a step is a gripper joint
};

// A joint of the gripper (driven or mimic), in canonical form, and its value as a function of
// the opening fraction f in [0, 1]:
//   value(f) = multiplier * (closed + f * (open - closed)) + offset   (mimic: of its master)
struct GripperJoint {
  std::string name;
  JointType type = JointType::kPrismatic;
  Eigen::Isometry3d before = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d after = Eigen::Isometry3d::Identity();
  double closed = 0.0;      // rad or m, at f = 0 (driven joint; mimic: the master's)
  double open = 0.0;        // rad or m, at f = 1
  double multiplier = 1.0;  // mimic: <mimic multiplier>; driven: 1
  double offset = 0.0;      // mimic: <mimic offset>; driven: 0
  std::string mimics;       // the master's name, empty for a driven joint
  double value(double fraction) const;
  Eigen::Isometry3d transform(double fraction) const;  // before * Z(value) * after
};

struct Gripper {
  std::vector<GripperJoint> joints;  // driven ones first, then mimic ones
  double max_opening_m = 0.08;       // the physical opening between the fingers at f = 1
  // The opening in metres -> the fraction (clamped to [0, 1]).
  double fraction(double opening_m) const;
};

// One entry of the robot file's `allowed_collisions:` (geometry/allowed_collisions.hpp): two
// URDF links never checked against each other, and why (adjacent, always, never, constant or
// user).
struct AllowedCollisionEntry {
  std::string a, b;
  std::string reason = "user";
};

struct RobotDescription {
  RobotModelPtr model;  // the chain root -> tip
  std::string name;
  std::string source;               // the file given (robot file, URDF or DH table)
  std::string urdf_path;            // empty for a DH robot
  std::string urdf_text;            // empty for a DH robot
  std::string root_link, tip_link;  // URDF link names (empty for a DH robot)
  std::vector<RobotLink> links;     // every URDF link
  std::optional<Gripper> gripper;
  std::vector<std::string> package_paths;  // from the robot file, absolute
  std::string body_file;                   // body override (absolute), empty: from the URDF
  std::optional<MarkerMount> marker;       // from the robot file or NAME.marker.yaml
  // The robot file's allowed-collision matrix; unset: none stored (geometry computes one).
  std::optional<std::vector<AllowedCollisionEntry>> allowed_collisions;
  const RobotLink* link(const std::string& name) const;
  // T_frame_link for link `index` at the gripper opening fraction (identity steps: I).
  Eigen::Isometry3d T_frame_link(std::size_t index, double gripper_fraction) const;
};

// The URDF a robot server hands its clients (GetInfo) so they can draw the same arm: the
// robot's own URDF text, or for a DH table the URDF of the same arm beside it
// (data/robots/puma560.yaml -> puma560.urdf); empty when there is none.
std::string urdf_text_for_clients(const RobotDescription& description);

// What a command's --robot / --tip say.
struct RobotSpec {
  RobotSpec() = default;
  // Implicit, so that {"ur6"} and {"arm.urdf", "tcp"} read as what they say.
  RobotSpec(std::string name_or_path_,  // NOLINT(google-explicit-constructor)
            std::string tip_ = {}, std::vector<std::string> package_paths_ = {})
      : name_or_path(std::move(name_or_path_)),
        tip(std::move(tip_)),
        package_paths(std::move(package_paths_)) {}

  std::string name_or_path;  // shipped name, robot file (.yaml with `urdf:`), DH table, .urdf
  std::string tip;           // tip link; empty: the robot file's, else the single leaf
  // --package-path: searched first for package:// URIs (core/resource_uri.hpp), then the
  // robot file's package_paths, then ROS_PACKAGE_PATH.
  std::vector<std::string> package_paths;
};

// Loads any of the forms above. Errors name the file and what is wrong; a tree with several
// leaves and no tip lists the candidate tips.
Result<RobotDescription> load_robot_description(const RobotSpec& spec);
// A URDF's text as a description (a robot server's GetInfo gives one): the chain to `tip`
// (empty: the single leaf), its links by name; no companion files (marker, body), no meshes
// read. `source` names it in messages.
Result<RobotDescription> parse_urdf_description(const std::string& text, const std::string& source,
                                                const std::string& tip = "");

}  // namespace telear::core
