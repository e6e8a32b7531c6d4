#include "telear/core/arm_body.hpp"

#include "telear/core/companion_file.hpp"

#include <algorithm>
#include <cassert>
#include <filesystem>

#include "telear/core/robot_loader.hpp"

namespace telear::core {
namespace {

constexpr float kMinLength = 1e-6f;

int segments_of(const ShapeSpec& shape, const BodyDescription& d, const ArmBodyOptions& o) {
  if (o.segments_override > 0) return std::max(o.segments_override, kMinCylinderSegments);
  return shape.segments > 0 ? shape.segments : d.default_segments;
}

void append_shape(Mesh& mesh, const ShapeSpec& shape, int segments) {
  switch (shape.kind) {
    case ShapeSpec::Kind::kCylinder:
      append_cylinder(mesh, shape.from, shape.to, shape.radius, segments, shape.colour);
      break;
    case ShapeSpec::Kind::kPrism:
      append_tapered_box(mesh, shape.from, shape.to, shape.size_from, shape.size_to, shape.up,
                         shape.colour);
      break;
    case ShapeSpec::Kind::kBox:
      append_box(mesh, shape.centre, shape.size, shape.colour);
      break;
  }
}

ShapeSpec cylinder(const Eigen::Vector3f& from, const Eigen::Vector3f& to, float radius,
                   const Eigen::Vector3f& colour) {
  ShapeSpec s;
  s.kind = ShapeSpec::Kind::kCylinder;
  s.from = from;
  s.to = to;
  s.radius = radius;
  s.colour = colour;
  return s;
}

float finger_half_width(const GripperSpec& g) {
  return 0.5f * std::abs(g.finger_size.dot(g.axis));
}

}  // namespace

std::size_t ArmBody::triangle_count() const {
  std::size_t n = 0;
  for (const BodyPart& p : parts) n += p.mesh.triangle_count();
  return n;
}

std::size_t ArmBody::line_count() const {
  std::size_t n = 0;
  for (const BodyPart& p : parts) n += p.mesh.line_count();
  return n;
}

Eigen::Isometry3f T_link_finger(const GripperSpec& gripper, int side, float opening) {
  const float w = std::clamp(opening, 0.0f, gripper.max_opening);
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.translation() = gripper.centre +
                    static_cast<float>(side) * (w / 2 + finger_half_width(gripper)) * gripper.axis;
  return T;
}

Eigen::Isometry3f T_link_moving_part(const std::vector<AttachmentStep>& steps,
                                     const Gripper& gripper, float opening_m) {
  const double f = gripper.fraction(opening_m);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (const AttachmentStep& step : steps) {
    if (step.gripper_joint < 0) {
      T = T * step.fixed;
    } else {
      assert(static_cast<std::size_t>(step.gripper_joint) < gripper.joints.size() &&
             "T_link_moving_part(): gripper joint index out of range");
      T = T * gripper.joints[static_cast<std::size_t>(step.gripper_joint)].transform(f);
    }
  }
  return T.cast<float>();
}

float ArmBody::max_gripper_opening() const {
  if (gripper) return gripper->max_opening;
  if (gripper_joints) return static_cast<float>(gripper_joints->max_opening_m);
  return 0.0f;
}

float ArmBody::default_gripper_opening() const {
  if (gripper) return gripper->opening;
  return 0.5f * max_gripper_opening();
}

Eigen::Isometry3f ArmBody::T_link_part(int part, float gripper_opening) const {
  const BodyPart& p = parts[static_cast<std::size_t>(part)];
  if (p.finger_side != 0 && gripper) return T_link_finger(*gripper, p.finger_side, gripper_opening);
  if (!p.steps.empty() && gripper_joints) {
    return T_link_moving_part(p.steps, *gripper_joints, gripper_opening);
  }
  return Eigen::Isometry3f::Identity();
}

ArmBody build_arm_body(const BodyDescription& description, const ArmBodyOptions& options) {
  ArmBody body;
  body.dof = static_cast<int>(description.links.size()) - 1;
  assert(body.dof >= 1 && "build_arm_body(): the description has no links");
  for (std::size_t i = 0; i < description.links.size(); ++i) {
    BodyPart part;
    part.name = i == 0 ? "base" : "link" + std::to_string(i);
    part.link = static_cast<int>(i);
    for (const ShapeSpec& shape : description.links[i]) {
      append_shape(part.mesh, shape, segments_of(shape, description, options));
    }
    if (i < description.link_meshes.size()) part.mesh.append(description.link_meshes[i]);
    body.parts.push_back(std::move(part));
  }
  if (description.gripper) {
    const GripperSpec& g = *description.gripper;
    assert(g.link >= 0 && g.link <= body.dof && "build_arm_body(): gripper link out of range");
    body.gripper = g;
    append_box(body.parts[static_cast<std::size_t>(g.link)].mesh, g.palm_centre, g.palm_size,
               g.colour);
    for (int side : {-1, +1}) {
      BodyPart finger;
      finger.name = side < 0 ? "finger_left" : "finger_right";
      finger.link = g.link;
      finger.finger_side = side;
      // Built once, centred in its own frame; the opening only moves T_link_finger.
      append_box(finger.mesh, Eigen::Vector3f::Zero(), g.finger_size, g.colour);
      body.parts.push_back(std::move(finger));
    }
  }
  assert((description.link_meshes.empty() ||
          description.link_meshes.size() == description.links.size()) &&
         "build_arm_body(): link_meshes must be empty or one per link");
  assert((description.moving_parts.empty() || description.gripper_joints) &&
         "build_arm_body(): moving parts need the gripper joints that drive them");
  body.gripper_joints = description.gripper_joints;
  for (const MovingPartSpec& moving : description.moving_parts) {
    assert(moving.link >= 0 && moving.link <= body.dof && "build_arm_body(): moving part frame");
    BodyPart part;
    part.name = moving.name;
    part.link = moving.link;
    part.steps = moving.steps;
    part.mesh = moving.mesh;  // built once; the opening only moves T_link_moving_part
    body.parts.push_back(std::move(part));
  }
  return body;
}

BodyDescription default_body_description(const RobotModel& model) {
  BodyDescription d;
  d.source = "default";
  d.default_segments = 16;
  const int n = model.dof();
  d.links.resize(static_cast<std::size_t>(n) + 1);

  // Size the cylinders from the arm's reach so that a 1 m arm and a 10 cm arm both look
  // like arms.
  double reach = model.T_flange_tool().translation().norm();
  for (const Joint& j : model.joints()) {
    reach += j.before.translation().norm() + j.after.translation().norm();
  }
  const float radius = std::clamp(static_cast<float>(0.035 * reach), 0.005f, 0.1f);
  const Eigen::Vector3f link_colour(0.72f, 0.72f, 0.75f);
  const Eigen::Vector3f joint_colour(0.45f, 0.5f, 0.6f);

  // The base: a disc under frame 0.
  d.links[0].push_back(cylinder(Eigen::Vector3f(0, 0, -radius), Eigen::Vector3f::Zero(),
                                2.0f * radius, joint_colour));
  for (int k = 0; k < n; ++k) {
    const Joint& j = model.joint(k);
    auto& parent = d.links[static_cast<std::size_t>(k)];
    auto& child = d.links[static_cast<std::size_t>(k) + 1];
    // Rigid in frame k: the offset to the joint (`before`) and the joint's axis.
    const Eigen::Vector3f joint_origin = j.before.translation().cast<float>();
    const Eigen::Vector3f joint_axis = j.before.linear().col(2).cast<float>();
    if (joint_origin.norm() > kMinLength) {
      parent.push_back(cylinder(Eigen::Vector3f::Zero(), joint_origin, radius, link_colour));
    }
    parent.push_back(cylinder(joint_origin - 1.3f * radius * joint_axis,
                              joint_origin + 1.3f * radius * joint_axis, 1.3f * radius,
                              joint_colour));
    // Rigid in frame k+1: the offset after the joint (`after`), split into its part along
    // the joint axis and the rest (a DH row's d, then a), so DH links look like L shapes.
    const Eigen::Isometry3f after = j.after.cast<float>();
    const Eigen::Isometry3f after_inv = after.inverse();
    const Eigen::Vector3f t = after.translation();
    const Eigen::Vector3f p_joint = after_inv * Eigen::Vector3f::Zero();
    const Eigen::Vector3f p_corner = after_inv * Eigen::Vector3f(0, 0, t.z());
    if ((p_corner - p_joint).norm() > kMinLength) {
      child.push_back(cylinder(p_joint, p_corner, radius, link_colour));
    }
    if (p_corner.norm() > kMinLength) {
      child.push_back(cylinder(p_corner, Eigen::Vector3f::Zero(), radius, link_colour));
    }
  }
  const Eigen::Vector3f tool = model.T_flange_tool().translation().cast<float>();
  if (tool.norm() > kMinLength) {
    d.links[static_cast<std::size_t>(n)].push_back(
        cylinder(Eigen::Vector3f::Zero(), tool, 0.6f * radius, joint_colour));
  }
  return d;
}

std::string find_body_file(const RobotModel& model) {
  return find_companion_file(model, ".body.yaml");
}

}  // namespace telear::core
