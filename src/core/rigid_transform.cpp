#include "telear/core/rigid_transform.hpp"

#include <Eigen/Dense>

#include "telear/core/number_format.hpp"

namespace telear::core {

std::string rigid_transform_problem(const Eigen::Matrix4d& T, double tolerance) {
  const double last_row = (T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff();
  if (last_row > tolerance) return "its last row is not 0 0 0 1";
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double orthonormality =
      (R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthonormality > tolerance) {
    return "its rotation block is not orthonormal (R R^T - I is off by " +
           format_number(orthonormality, "%.3g") + "; tolerance " + format_number(tolerance) + ")";
  }
  if (R.determinant() < 0.0) return "its rotation block is a reflection (determinant -1)";
  return {};
}

}  // namespace telear::core
