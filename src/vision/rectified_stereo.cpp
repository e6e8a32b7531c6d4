#include "telear/vision/rectified_stereo.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace telear::vision {
namespace {

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// Equal to a millionth, relative: both files come from one rectification, but a file may have
// been written with fewer digits than a double holds.
bool same(double a, double b) {
  return std::abs(a - b) <= 1e-6 * std::max(std::abs(a), std::abs(b));
}

}  // namespace

Result<Eigen::Isometry3d> right_from_left_rectified(const Rectification& left,
                                                    const Rectification& right) {
  if (left.tx() != 0.0 || left.ty() != 0.0) {
    return Error{"left: projection_matrix: Tx = P[0][3] = " + number(left.tx()) +
                 " and Ty = P[1][3] = " + number(left.ty()) +
                 " must be 0 for the left camera of a pair (are the two files swapped?)"};
  }
  if (right.tx() == 0.0 && right.ty() == 0.0) {
    return Error{
        "right: projection_matrix: Tx = P[0][3] is 0, so the pair has no baseline (a rectified "
        "right camera has Tx = -fx' * B, B the baseline in metres); is it a mono camera_info "
        "file?"};
  }
  const char* names[] = {"fx' ([0][0])", "fy' ([1][1])"};
  for (int i = 0; i < 2; ++i) {
    if (!same(left.P(i, i), right.P(i, i))) {
      return Error{"right: projection_matrix: " + std::string(names[i]) + " = " +
                   number(right.P(i, i)) + " differs from the left camera's " +
                   number(left.P(i, i)) +
                   "; the two files are not one rectified pair (they share fx' and fy')"};
    }
  }
  const Eigen::Matrix3d K = right.P.leftCols<3>();
  const Eigen::Vector3d t = K.inverse() * right.P.col(3);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = right.R.transpose() * left.R;
  T.translation() = right.R.transpose() * t;
  return T;
}

}  // namespace telear::vision
