#include "telear/session/marker_visibility.hpp"

#include <algorithm>
#include <cmath>

#include "telear/core/angles.hpp"
#include "telear/core/number_format.hpp"

namespace telear::session {
namespace {

// Sight lines start this far out of the marker's plane, towards the camera: the plate the
// marker is printed on is not part of the body, and a nominal body that reaches around the
// plate (the wrist's cylinder drawn wider than the real one) must not count as a hit.
constexpr double kStartOffsetM = 0.02;

std::vector<Eigen::Vector3d> triangles_of(const core::Mesh& mesh) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(mesh.triangles.size());
  for (const std::uint32_t index : mesh.triangles) {
    const float* p = mesh.vertices[index].position;
    out.emplace_back(p[0], p[1], p[2]);
  }
  return out;
}

void bound(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d& centre, double& radius) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  centre = box.center();
  radius = 0.0;
  for (const Eigen::Vector3d& p : points) radius = std::max(radius, (p - centre).norm());
}

// Möller-Trumbore: does the segment a + t (b - a), t in (0, 1), cross triangle (p0, p1, p2)?
bool segment_crosses(const Eigen::Vector3d& a, const Eigen::Vector3d& d, const Eigen::Vector3d& p0,
                     const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-14) return false;  // parallel
  const double inv = 1.0 / det;
  const Eigen::Vector3d s = a - p0;
  const double u = inv * s.dot(h);
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d qv = s.cross(e1);
  const double v = inv * d.dot(qv);
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = inv * e2.dot(qv);
  return t > 0.0 && t < 1.0;
}

}  // namespace

MarkerVisibility::MarkerVisibility(const core::RobotModel& model, const core::MarkerMount& marker,
                                   const core::ArmBody* body, const core::Workspace* workspace,
                                   const MarkerVisibilityOptions& options,
                                   const std::optional<vision::RegistrationTarget>& target)
    : model_(model), marker_(marker), options_(options), data_(model) {
  if (body) {
    const float opening = body->default_gripper_opening();
    for (int k = 0; k < body->part_count(); ++k) {
      const core::BodyPart& part = body->parts[static_cast<std::size_t>(k)];
      if (part.mesh.triangles.empty() || part.link < 0 || part.link > model.dof()) continue;
      Occluder o;
      o.name = part.name;
      o.link = part.link;
      o.T_link_part = body->T_link_part(k, opening).cast<double>();
      o.triangles = triangles_of(part.mesh);
      bound(o.triangles, o.centre, o.radius);
      occluders_.push_back(std::move(o));
    }
  }
  if (workspace) {
    for (const core::WorkspaceObject& object : workspace->objects) {
      Occluder o;
      o.name = object.name;
      o.T_link_part = object.T_base_object;
      o.triangles = triangles_of(core::workspace_object_mesh(object, 16));
      if (o.triangles.empty()) continue;
      bound(o.triangles, o.centre, o.radius);
      occluders_.push_back(std::move(o));
    }
  }
  // Half the target's size: a marker's black square, a board's chessboard (its corners and
  // the markers they are interpolated from lie inside it).
  const vision::RegistrationTarget seen =
      target ? *target : vision::registration_target_from_mount(marker);
  const Eigen::Vector2d half = seen.is_board()
                                   ? Eigen::Vector2d(0.5 * seen.squares_x * seen.square_m,
                                                     0.5 * seen.squares_y * seen.square_m)
                                   : Eigen::Vector2d::Constant(0.5 * seen.side_m);
  corners_ = {Eigen::Vector3d(-half.x(), half.y(), 0.0), Eigen::Vector3d(half.x(), half.y(), 0.0),
              Eigen::Vector3d(half.x(), -half.y(), 0.0),
              Eigen::Vector3d(-half.x(), -half.y(), 0.0)};
  cell_m_ = (seen.is_board() ? seen.marker_m : seen.side_m) / seen.marker_cells();
  const Eigen::Vector2d h = half * options.sight_scale;
  // A marker: 3 x 3 lines. A board: at most a square apart, so that no arm link can stand
  // between two lines and hide a few corners (a big board behind the upper arm kept 4 of its
  // 9 corners, 0.5 px off, and turned the registration 1.6 mm).
  const Eigen::Vector2i steps =
      seen.is_board() ? Eigen::Vector2i(static_cast<int>(std::ceil(2.0 * h.x() / seen.square_m)),
                                        static_cast<int>(std::ceil(2.0 * h.y() / seen.square_m)))
                            .cwiseMax(2)
                      : Eigen::Vector2i(2, 2);
  for (int i = 0; i <= steps.x(); ++i) {
    for (int j = 0; j <= steps.y(); ++j) {
      sight_points_.emplace_back(h.x() * (2.0 * i / steps.x() - 1.0),
                                 h.y() * (2.0 * j / steps.y() - 1.0), 0.0);
    }
  }
}

Eigen::Isometry3d MarkerVisibility::marker_pose(const Eigen::VectorXd& q) {
  if (data_.q.size() != q.size() || data_.q != q) core::forward_kinematics(model_, data_, q);
  return data_.T_base_link.back() * marker_.T_flange_marker;
}

bool MarkerVisibility::segment_hits(const Occluder& occluder, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b) {
  // The bounding sphere first: the distance from its centre to the segment.
  const Eigen::Vector3d d = b - a;
  const double t = std::clamp((occluder.centre - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  if ((a + t * d - occluder.centre).norm() > occluder.radius) return false;
  const auto& tri = occluder.triangles;
  for (std::size_t i = 0; i + 2 < tri.size(); i += 3) {
    if (segment_crosses(a, d, tri[i], tri[i + 1], tri[i + 2])) return true;
  }
  return false;
}

std::string MarkerVisibility::hidden_reason(const vision::CameraModel& camera,
                                            const Eigen::VectorXd& q) {
  const Eigen::Isometry3d T_base_marker = marker_pose(q);
  const Eigen::Vector3d centre = T_base_marker.translation();
  const Eigen::Vector3d camera_centre = camera.T_cam_base.inverse().translation();
  const Eigen::Vector3d normal = T_base_marker.linear().col(2);
  const Eigen::Vector3d to_camera = (camera_centre - centre).normalized();
  const double cos_view = normal.dot(to_camera);
  if (cos_view < std::cos(core::radians_from_degrees(options_.max_view_angle_deg))) {
    return "faces away (" +
           core::format_fixed(
               core::degrees_from_radians(std::acos(std::clamp(cos_view, -1.0, 1.0))), 0) +
           " deg)";
  }
  for (const Eigen::Vector3d& p : corners_) {
    const auto uv = camera.project(T_base_marker * p);
    if (!uv || uv->x() < options_.margin_px || uv->y() < options_.margin_px ||
        uv->x() > camera.width - options_.margin_px ||
        uv->y() > camera.height - options_.margin_px) {
      return "outside the image";
    }
  }
  // A cell at the centre, along the target's x and y: its smaller projected extent.
  const auto c = camera.project(centre);
  const auto cx = camera.project(T_base_marker * Eigen::Vector3d(cell_m_, 0.0, 0.0));
  const auto cy = camera.project(T_base_marker * Eigen::Vector3d(0.0, cell_m_, 0.0));
  if (!c || !cx || !cy) return "outside the image";
  const double cell_px = std::min((*cx - *c).norm(), (*cy - *c).norm());
  if (cell_px < options_.min_cell_px) return "cells of " + core::format_fixed(cell_px, 1) + " px";
  for (const Occluder& o : occluders_) {
    const Eigen::Isometry3d T_part_base =
        (o.link < 0 ? o.T_link_part
                    : data_.T_base_link[static_cast<std::size_t>(o.link)] * o.T_link_part)
            .inverse();
    const Eigen::Vector3d c = T_part_base * camera_centre;
    for (const Eigen::Vector3d& s : sight_points_) {
      const Eigen::Vector3d p = T_base_marker * s + kStartOffsetM * to_camera;
      if (segment_hits(o, T_part_base * p, c)) return "hidden by " + o.name;
    }
  }
  return {};
}

}  // namespace telear::session
