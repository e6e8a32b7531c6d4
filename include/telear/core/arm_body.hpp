#pragma once
// The arm's body: the solid that is drawn around the kinematic skeleton (the seed paper's
// "graphical arm"). No GL here: meshes are plain CPU data that the renderer uploads once.
//
// The seed's data structure, kept: one object per link with its own vertex buffer. Each
// part's mesh is built ONCE in its own frame; when the arm moves, only the part's 4x4 matrix
// T_base_part changes (telear/core/arm_body_pose.hpp), never its vertices.
//
// Parts, in this order (part index = link index for the links):
//   parts[0]       link 0, the fixed base (frame T_base_link[0] = identity),
//   parts[i]       link i = 1..n, rigidly attached to frame i (T_base_link[i]),
//   parts[n+1..]   the gripper's two fingers, attached to the gripper's link with an offset
//                  that depends on the opening: the opening moves the fingers' matrices,
//                  it does not rebuild their meshes;
//   then           the moving parts (a URDF robot's finger links): a prebuilt mesh on frame
//                  `link` whose pose in that frame is the product of its attachment steps,
//                  fixed transforms and gripper joints evaluated at the opening fraction
//                  (core::Gripper, robot_description.hpp):
//                    T_link_part(w) = steps[0](f) * steps[1](f) * ...,  f = fraction(w).
// A link with no shapes has an empty mesh (drawn as nothing) so that indices stay aligned.
// A link's part holds its primitives followed by its prebuilt mesh (link_meshes), if any:
// a URDF robot's visuals of every link riding on that frame, merged by the geometry layer.
//
// Where the shapes come from: a body file beside the robot (data/robots/NAME.body.yaml,
// format in docs/rendering.md) describes per link the primitives (cylinder, tapered prism,
// box), their placement in the link frame, radius, colour and segment count. A robot with no
// body file gets default_body_description(): a cylinder along each link offset and a short
// one along each joint axis, sized from the arm's reach.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/mesh.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// One primitive of a link, in the link's frame (metres, colours 0..1).
struct ShapeSpec {
  enum class Kind { kCylinder, kPrism, kBox };
  Kind kind = Kind::kCylinder;
  Eigen::Vector3f from = Eigen::Vector3f::Zero();    // cylinder / prism axis start
  Eigen::Vector3f to = Eigen::Vector3f::UnitZ();     // cylinder / prism axis end
  float radius = 0.05f;                              // cylinder
  int segments = 0;                                  // cylinder; 0: the body's default
  Eigen::Vector2f size_from{0.1f, 0.1f};             // prism (width, height) at `from`
  Eigen::Vector2f size_to{0.1f, 0.1f};               // prism (width, height) at `to`
  Eigen::Vector3f up = Eigen::Vector3f::UnitY();     // prism: direction of the height
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // box
  Eigen::Vector3f size = Eigen::Vector3f::Ones();    // box full size (x, y, z)
  Eigen::Vector3f colour{0.7f, 0.7f, 0.72f};
};

// A parallel gripper of boxes on link `link`: a palm (part of that link's mesh) and two
// fingers that slide symmetrically along `axis`. With opening w the fingers' inner faces
// are w apart: finger k's centre is centre + s_k (w / 2 + finger_size.dot(|axis|) / 2) axis,
// s = -1, +1.
struct GripperSpec {
  int link = 0;                                      // 1..n
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // between the fingers, link frame
  Eigen::Vector3f axis = Eigen::Vector3f::UnitY();   // unit opening direction, link frame
  Eigen::Vector3f palm_centre = Eigen::Vector3f::Zero();
  Eigen::Vector3f palm_size{0.08f, 0.12f, 0.02f};
  Eigen::Vector3f finger_size{0.02f, 0.015f, 0.06f};  // axis-aligned in the link frame
  float opening = 0.04f;                              // default opening, m
  float max_opening = 0.08f;
  Eigen::Vector3f colour{0.35f, 0.35f, 0.38f};
};

// A prebuilt mesh that moves with the gripper opening (a URDF finger link), in its own frame.
struct MovingPartSpec {
  std::string name;                   // the URDF link's name
  int link = 0;                       // the chain frame it rides on, 0..n
  std::vector<AttachmentStep> steps;  // frame -> part; gripper steps index gripper_joints
  Mesh mesh;
};

// The declarative body: what the body file holds, or what the geometry layer built from a
// URDF's visuals (prebuilt meshes, moving parts and the joints that drive them).
struct BodyDescription {
  std::string source;                         // file it came from, or "default"
  int default_segments = 16;                  // cylinders without their own count
  std::vector<std::vector<ShapeSpec>> links;  // n + 1 entries: link 0 (base) .. link n
  std::optional<GripperSpec> gripper;
  std::vector<Mesh> link_meshes;             // empty, or n + 1 entries appended to the links
  std::vector<MovingPartSpec> moving_parts;  // after the fingers, in this order
  std::optional<Gripper> gripper_joints;     // drives moving_parts' gripper steps
};

// Build-time choices (the CLI's --segments, the benchmark's 8 / 50 segments).
struct ArmBodyOptions {
  int segments_override = 0;  // > 0: every cylinder gets this many segments
};

struct BodyPart {
  std::string name;                   // "link3", "finger_left", a URDF link name ...
  int link = 0;                       // the frame the part moves with: 0 (base) .. n
  int finger_side = 0;                // -1 / +1 for a gripper finger, 0 for a link
  std::vector<AttachmentStep> steps;  // a moving part: frame -> part (empty otherwise)
  Mesh mesh;                          // in the part's own frame
  bool moves_with_opening() const { return finger_side != 0 || !steps.empty(); }
};

struct ArmBody {
  int dof = 0;
  std::vector<BodyPart> parts;  // see the header comment for the order
  std::optional<GripperSpec> gripper;
  std::optional<Gripper> gripper_joints;  // drives the moving parts' gripper steps

  int link_part_count() const { return dof + 1; }
  int part_count() const { return static_cast<int>(parts.size()); }
  std::size_t triangle_count() const;
  std::size_t line_count() const;
  bool has_gripper() const { return gripper.has_value() || gripper_joints.has_value(); }
  // The largest opening (m): the primitive gripper's, else the URDF gripper's; 0 without one.
  float max_gripper_opening() const;
  // The opening a new pose starts at: the primitive gripper's default, else half the maximum.
  float default_gripper_opening() const;
  // The opening (m) of a robot state's gripper fraction 0 (closed) .. 1 (open), clamped; 0
  // without a gripper. The wire and the robot report fractions, the body draws metres.
  float gripper_opening_m(double fraction) const {
    if (!has_gripper()) return 0.0f;
    return static_cast<float>(fraction < 0.0   ? 0.0
                              : fraction > 1.0 ? 1.0
                                               : fraction) *
           max_gripper_opening();
  }
  // Pose of part `part` in its link's frame at the given gripper opening (identity for a
  // link part). The opening is clamped to [0, max_gripper_opening()].
  Eigen::Isometry3f T_link_part(int part, float gripper_opening) const;
};

// Pose of finger `side` (-1 / +1) in the gripper's link frame at `opening` (clamped).
Eigen::Isometry3f T_link_finger(const GripperSpec& gripper, int side, float opening);

// Pose of a moving part in its frame: the steps' product with the gripper joints at the
// opening (m, turned into a fraction by `gripper`, which clamps it).
Eigen::Isometry3f T_link_moving_part(const std::vector<AttachmentStep>& steps,
                                     const Gripper& gripper, float opening_m);

// Builds the meshes. The description must be valid (parse_body_yaml validates files).
ArmBody build_arm_body(const BodyDescription& description, const ArmBodyOptions& options = {});

// Cylinders along each link's offsets and joint axes, for robots with no body file.
BodyDescription default_body_description(const RobotModel& model);

// Parses a body file for `model` (link count and robot name must match; a file with
// `frames: standard_dh` needs a model with a DH table). Untrusted input: errors name the
// file, the entry and what is wrong.
Result<BodyDescription> parse_body_yaml(const std::string& text, const std::string& source,
                                        const RobotModel& model);
Result<BodyDescription> load_body_yaml_file(const std::string& path, const RobotModel& model);

// The body file that belongs to `model`: beside its source (puma560.yaml ->
// puma560.body.yaml), else data/robots/NAME.body.yaml; empty when there is none.
std::string find_body_file(const RobotModel& model);

// find_body_file + load, or the default description when the robot has no body file or its
// body file is written in DH frames and the model has none (e.g. the URDF of the same arm,
// whose link frames differ from the DH frames).
Result<BodyDescription> body_description_for(const RobotModel& model);

}  // namespace telear::core
