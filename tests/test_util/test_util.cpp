#include "test_util/test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "telear/core/random_configuration.hpp"
#include "telear/core/robot_loader.hpp"

namespace telear::test {

std::string data_path(const std::string& relative) {
  return std::string(TELEAR_TEST_DATA_DIR) + "/" + relative;
}

core::RobotModelPtr puma560() {
  auto model = core::load_robot(data_path("robots/puma560.yaml"));
  if (!model) {
    ADD_FAILURE() << model.error().message;
    return nullptr;
  }
  return *model;
}

Eigen::VectorXd random_configuration(const core::RobotModel& model, std::mt19937_64& rng) {
  return core::random_configuration(model, rng);
}

Eigen::Matrix4d dh_product(const std::vector<core::DhRow>& rows, const Eigen::VectorXd& q) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (size_t i = 0; i < rows.size(); ++i) {
    const double theta = q[static_cast<Eigen::Index>(i)] + rows[i].offset;
    const double ct = std::cos(theta), st = std::sin(theta);
    const double ca = std::cos(rows[i].alpha), sa = std::sin(rows[i].alpha);
    Eigen::Matrix4d A;
    A << ct, -st * ca, st * sa, rows[i].a * ct,  //
        st, ct * ca, -ct * sa, rows[i].a * st,   //
        0, sa, ca, rows[i].d,                    //
        0, 0, 0, 1;
    T = T * A;
  }
  return T;
}

double max_abs_diff(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

}  // namespace telear::test
