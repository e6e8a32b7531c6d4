#include "telear/sim/flange_target.hpp"

#include "target_print.hpp"

namespace telear::sim {
namespace {

// Corners in printed order (top-left, top-right, bottom-right, bottom-left), seen from +z with
// x right and y up: that order is clockwise, so the triangles go the other way round.
void add_face(core::Mesh& mesh, const std::array<Eigen::Vector3d, 4>& c, double z,
              const Eigen::Vector3f& colour) {
  const Eigen::Vector3f n(0.f, 0.f, 1.f);
  std::array<std::uint32_t, 4> i{};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3f p(static_cast<float>(c[k].x()), static_cast<float>(c[k].y()),
                            static_cast<float>(z));
    i[k] = mesh.add_vertex(p, n, colour);
  }
  mesh.triangles.insert(mesh.triangles.end(), {i[0], i[3], i[2], i[0], i[2], i[1]});
}

}  // namespace

FlangeTarget make_flange_target(const vision::RegistrationTarget& target,
                                const Eigen::Isometry3d& T_flange_target) {
  FlangeTarget out;
  out.target = target;
  out.T_flange_target = T_flange_target;
  for (const auto& quad : vision::registration_target_dark_quads(target)) {
    add_face(out.mesh, quad, 0.0, kBlack);
  }
  const Eigen::Vector2d size = target.printed_size_m();
  const double hx = 0.5 * size.x(), hy = 0.5 * size.y();
  add_face(out.mesh,
           {Eigen::Vector3d(-hx, hy, 0), Eigen::Vector3d(hx, hy, 0), Eigen::Vector3d(hx, -hy, 0),
            Eigen::Vector3d(-hx, -hy, 0)},
           -0.0002, kWhite);
  // The backing plate behind the print (front face 0.3 mm behind it), a little larger.
  const float margin = static_cast<float>(0.05 * std::max(size.x(), size.y()));
  core::append_box(out.mesh, Eigen::Vector3f(0.f, 0.f, -0.0053f),
                   Eigen::Vector3f(static_cast<float>(size.x()) + margin,
                                   static_cast<float>(size.y()) + margin, 0.01f),
                   Eigen::Vector3f(0.18f, 0.18f, 0.2f));
  out.mesh.transform(T_flange_target.matrix().cast<float>());
  for (const Eigen::Vector3d& p : target.points()) out.points_flange.push_back(T_flange_target * p);
  return out;
}

}  // namespace telear::sim
