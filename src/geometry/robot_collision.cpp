#include "telear/geometry/robot_collision.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace telear::geometry {
namespace {

using Kind = core::GeometryElement::Kind;

// Fractions at which a gripper-driven body's extent is measured: the joints are monotonic in
// the fraction for the grippers telear knows, so the ends and the middle bound it; a small
// margin covers the rest.
constexpr double kFingerRadiusMargin_m = 0.005;

CollisionShape box_shape(const Eigen::Vector3d& centre, const Eigen::Matrix3d& R,
                         const Eigen::Vector3d& size) {
  CollisionShape s;
  s.kind = Kind::kBox;
  s.T_link_shape.linear() = R;
  s.T_link_shape.translation() = centre;
  s.box_size = size;
  return s;
}

// A rotation whose z is `axis` (unit), with x and y any orthonormal completion.
Eigen::Matrix3d frame_along(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
}

// The DH body file's primitives (core/arm_body.hpp) as collision shapes of one link.
std::vector<CollisionShape> shapes_from_specs(const std::vector<core::ShapeSpec>& specs) {
  std::vector<CollisionShape> out;
  for (const core::ShapeSpec& spec : specs) {
    const Eigen::Vector3d from = spec.from.cast<double>(), to = spec.to.cast<double>();
    const Eigen::Vector3d along = to - from;
    const double length = along.norm();
    switch (spec.kind) {
      case core::ShapeSpec::Kind::kCylinder: {
        if (!(length > 0.0)) continue;
        CollisionShape s;
        s.kind = Kind::kCylinder;
        s.T_link_shape.linear() = frame_along(along / length);
        s.T_link_shape.translation() = (from + to) / 2.0;
        s.radius = spec.radius;
        s.length = length;
        out.push_back(std::move(s));
        break;
      }
      case core::ShapeSpec::Kind::kPrism: {
        // The box holding the tapered prism: as wide and high as its larger end.
        if (!(length > 0.0)) continue;
        const Eigen::Vector3d z = along / length;
        Eigen::Vector3d y = spec.up.cast<double>() - spec.up.cast<double>().dot(z) * z;
        y = y.norm() > 1e-9 ? y.normalized() : frame_along(z).col(1);
        Eigen::Matrix3d R;
        R.col(0) = y.cross(z);
        R.col(1) = y;
        R.col(2) = z;
        const Eigen::Vector2d size =
            spec.size_from.cast<double>().cwiseMax(spec.size_to.cast<double>());
        out.push_back(box_shape((from + to) / 2.0, R, Eigen::Vector3d(size.x(), size.y(), length)));
        break;
      }
      case core::ShapeSpec::Kind::kBox:
        out.push_back(box_shape(spec.centre.cast<double>(), Eigen::Matrix3d::Identity(),
                                spec.size.cast<double>()));
        break;
    }
  }
  return out;
}

Result<RobotCollisionModel> from_dh_body(const core::RobotDescription& d) {
  Result<core::BodyDescription> body = core::body_description_for(*d.model);
  if (!body) return body.error();
  RobotCollisionModel m;
  m.model = d.model;
  for (std::size_t k = 0; k < body->links.size(); ++k) {
    CollisionBody b;
    b.name = "link" + std::to_string(k);
    b.frame = static_cast<int>(k);
    b.shapes = shapes_from_specs(body->links[k]);
    if (body->gripper && body->gripper->link == static_cast<int>(k)) {
      const core::GripperSpec& g = *body->gripper;
      b.shapes.push_back(box_shape(g.palm_centre.cast<double>(), Eigen::Matrix3d::Identity(),
                                   g.palm_size.cast<double>()));
    }
    if (!b.shapes.empty()) m.bodies.push_back(std::move(b));
  }
  if (body->gripper) {
    m.box_gripper = body->gripper;
    for (int side : {-1, 1}) {
      CollisionBody b;
      b.name = side < 0 ? "finger_left" : "finger_right";
      b.frame = body->gripper->link;
      b.motion = CollisionBody::Motion::kBoxFinger;
      b.finger_side = side;
      b.shapes.push_back(box_shape(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                                   body->gripper->finger_size.cast<double>()));
      m.bodies.push_back(std::move(b));
    }
  }
  return m;
}

Result<RobotCollisionModel> from_urdf(const core::RobotDescription& d, const GeometryOptions& o) {
  Result<RobotCollisionGeometry> geometry = collision_geometry_for(d, o);
  if (!geometry) return geometry.error();
  RobotCollisionModel m;
  m.model = d.model;
  m.gripper = d.gripper;
  m.warnings = std::move(geometry->warnings);
  for (LinkCollision& lc : geometry->links) {
    const core::RobotLink& link = d.links[lc.link_index];
    CollisionBody b;
    b.name = lc.link;
    b.frame = lc.frame;
    b.shapes = std::move(lc.shapes);
    if (link.moves_with_gripper() && d.gripper) {
      b.motion = CollisionBody::Motion::kSteps;
      b.steps = link.steps;
    } else {
      b.T_frame_body = d.T_frame_link(lc.link_index, 0.0);
    }
    m.bodies.push_back(std::move(b));
  }
  return m;
}

double body_radius(const RobotCollisionModel& m, std::size_t b) {
  const CollisionBody& body = m.bodies[b];
  double radius = 0.0;
  const bool moves = body.motion != CollisionBody::Motion::kRigid;
  for (double f : moves ? std::vector<double>{0.0, 0.5, 1.0} : std::vector<double>{0.0}) {
    const Eigen::Isometry3d T = m.T_frame_body(b, f);
    for (const CollisionShape& s : body.shapes) {
      CollisionShape posed = s;
      posed.T_link_shape = T * s.T_link_shape;
      radius = std::max(radius, shape_radius_about_origin(posed));
    }
  }
  return moves ? radius + kFingerRadiusMargin_m : radius;
}

// lever[j][b] (see the header): joints j = 0..n-1 move frames j+1..n.
void compute_levers(RobotCollisionModel& m) {
  const core::RobotModel& model = *m.model;
  const int n = model.dof();
  m.lever.assign(static_cast<std::size_t>(n), std::vector<double>(m.bodies.size(), 0.0));
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const int k = m.bodies[b].frame;  // moved by joints 0..k-1
    const double rho = m.bodies[b].radius_about_frame_m;
    for (int j = 0; j < k && j < n; ++j) {
      const core::Joint& joint = model.joint(j);
      if (joint.type == core::JointType::kPrismatic) {
        m.lever[static_cast<std::size_t>(j)][b] = 1.0;
        continue;
      }
      double reach = rho + joint.after.translation().norm();
      for (int i = j + 1; i < k; ++i) {
        const core::Joint& next = model.joint(i);
        reach += next.before.translation().norm() + next.after.translation().norm();
        if (next.type == core::JointType::kPrismatic) {
          reach += std::max(std::abs(next.limits.lower), std::abs(next.limits.upper));
        }
      }
      m.lever[static_cast<std::size_t>(j)][b] = reach;
    }
  }
}

}  // namespace

double shape_radius_about_origin(const CollisionShape& s) {
  const double centre = s.T_link_shape.translation().norm();
  switch (s.kind) {
    case Kind::kBox:
      return centre + s.box_size.norm() / 2.0;
    case Kind::kCylinder:
      return centre + std::hypot(s.radius, s.length / 2.0);
    case Kind::kSphere:
      return centre + s.radius;
    case Kind::kMesh: {
      double r = 0.0;
      for (const core::MeshVertex& v : s.mesh.vertices) {
        const Eigen::Vector3d p(v.position[0], v.position[1], v.position[2]);
        r = std::max(r, (s.T_link_shape * p).norm());
      }
      return r;
    }
  }
  return centre;
}

int RobotCollisionModel::body_index(const std::string& name) const {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

Eigen::Isometry3d RobotCollisionModel::T_frame_body(std::size_t index, double f) const {
  const CollisionBody& b = bodies[index];
  f = std::clamp(f, 0.0, 1.0);
  switch (b.motion) {
    case CollisionBody::Motion::kRigid:
      return b.T_frame_body;
    case CollisionBody::Motion::kBoxFinger:
      assert(box_gripper && "T_frame_body(): a box finger without the box gripper");
      return core::T_link_finger(*box_gripper, b.finger_side,
                                 static_cast<float>(f) * box_gripper->max_opening)
          .cast<double>();
    case CollisionBody::Motion::kSteps: {
      assert(gripper && "T_frame_body(): a gripper link without the gripper");
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      for (const core::AttachmentStep& step : b.steps) {
        T = step.gripper_joint < 0
                ? T * step.fixed
                : T * gripper->joints[static_cast<std::size_t>(step.gripper_joint)].transform(f);
      }
      return T;
    }
  }
  return b.T_frame_body;
}

std::size_t RobotCollisionModel::attach(std::string name, std::vector<CollisionShape> shapes,
                                        const Eigen::Isometry3d& T_tool_body) {
  CollisionBody b;
  b.name = std::move(name);
  b.frame = model->dof();
  b.T_frame_body = model->T_flange_tool() * T_tool_body;
  b.shapes = std::move(shapes);
  bodies.push_back(std::move(b));
  const std::size_t index = bodies.size() - 1;
  bodies[index].radius_about_frame_m = body_radius(*this, index);
  compute_levers(*this);
  return index;
}

void update_motion_bounds(RobotCollisionModel& robot) {
  for (std::size_t b = 0; b < robot.bodies.size(); ++b) {
    robot.bodies[b].radius_about_frame_m = body_radius(robot, b);
  }
  compute_levers(robot);
}

Result<RobotCollisionModel> robot_collision_model(const core::RobotDescription& description,
                                                  const GeometryOptions& options) {
  Result<RobotCollisionModel> m =
      description.links.empty() ? from_dh_body(description) : from_urdf(description, options);
  if (!m) return m;
  update_motion_bounds(*m);
  return m;
}

}  // namespace telear::geometry
