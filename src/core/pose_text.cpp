#include "telear/core/pose_text.hpp"

#include <sstream>
#include <vector>

#include "telear/core/angles.hpp"
#include "telear/core/number_list.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/rigid_transform.hpp"

namespace telear::core {

Result<Eigen::Isometry3d> rigid_transform_from_text(const std::string& text,
                                                    const std::string& option) {
  std::string list = text;
  if (list.find(',') == std::string::npos) {
    std::string joined;
    std::istringstream words(text);
    std::string word;
    while (words >> word) joined += (joined.empty() ? "" : ",") + word;
    list = joined;
  }
  auto values = parse_number_list(list, option, 16);
  if (!values) return values.error();
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) M(r, c) = (*values)[static_cast<size_t>(4 * r + c)];
  }
  constexpr double kTolerance = 1e-4;
  if (const std::string problem = rigid_transform_problem(M, kTolerance); !problem.empty()) {
    return Error{option + " is not a rigid transform: " + problem};
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond(Eigen::Matrix3d(M.topLeftCorner<3, 3>())).normalized().toRotationMatrix();
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

Result<Eigen::Isometry3d> pose_from_text(const std::string& text, const std::string& option,
                                         bool degrees) {
  auto values = parse_number_list(text, option, 6);
  if (!values) {
    return Error{values.error().message + " (x,y,z in m, roll,pitch,yaw in " +
                 (degrees ? "deg)" : "rad)")};
  }
  const std::vector<double>& v = *values;
  Eigen::Vector3d rpy(v[3], v[4], v[5]);
  if (degrees) rpy = rpy.unaryExpr([](double a) { return radians_from_degrees(a); });
  return pose_from_xyz_rpy(Eigen::Vector3d(v[0], v[1], v[2]), rpy);
}

}  // namespace telear::core
