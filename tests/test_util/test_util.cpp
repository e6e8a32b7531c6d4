#include "test_util/test_util.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <stdexcept>

#include "telear/core/angles.hpp"
#include "test_util/temp_dir.hpp"

#include "telear/core/random_configuration.hpp"
#include "telear/core/robot_loader.hpp"

namespace telear::test {

std::string data_path(const std::string& relative) {
  // Appended piece by piece: GCC 12 at -O1 reports a false -Wstringop-overflow for the
  // chained operator+ on a string literal.
  std::string path = TELEAR_TEST_DATA_DIR;
  path += '/';
  path += relative;
  return path;
}

Eigen::VectorXd deg(std::initializer_list<double> values) {
  Eigen::VectorXd q(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double v : values) q[i++] = core::radians_from_degrees(v);
  return q;
}

Eigen::VectorXd q6(double a, double b, double c, double d, double e, double f) {
  Eigen::VectorXd q(6);
  q << a, b, c, d, e, f;
  return q;
}

core::RobotDescription robot_description(const std::string& robot) {
  auto description = core::load_robot_description({robot, "", {}});
  EXPECT_TRUE(description) << description.error().message;
  return std::move(*description);
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

namespace telear::test_files {
namespace fs = std::filesystem;

TempDir::TempDir(std::string_view label) {
  static std::atomic<unsigned> counter{0};
  const auto pid = static_cast<unsigned long>(::getpid());
  std::random_device rd;
  const fs::path base = fs::temp_directory_path();
  // create_directory is atomic and reports whether it made the folder: a name some other process
  // (or an older run) already holds is never shared, a new one is drawn instead.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path candidate =
        base / ("telear_" + std::string(label) + "_" + std::to_string(pid) + "_" +
                std::to_string(counter++) + "_" + std::to_string(rd()));
    if (fs::create_directory(candidate)) {
      path_ = candidate;
      return;
    }
  }
  throw std::runtime_error("TempDir: no fresh folder under " + base.string());
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string TempDir::file(const std::string& relative) const {
  const fs::path p = path_ / relative;
  fs::create_directories(p.parent_path());
  return p.string();
}

std::string TempDir::write(const std::string& relative, const std::string& text) const {
  const std::string p = file(relative);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

}  // namespace telear::test_files
