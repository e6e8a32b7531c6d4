// An independent reference for URDF kinematics: Orocos KDL's tree from Debian's kdl_parser
// (the same URDF text, parsed and chained by other code) and its recursive FK solver. For the
// PUMA URDF, each crafted movable URDF and every shipped robot file with `urdf:`, T_base_tip
// from telear equals KDL's at 1000 random configurations to 1e-12.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <random>

#include "telear/core/kinematics.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_loader.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::string path, tip;
};

std::vector<Case> cases() {
  const std::string urdf = std::string(TELEAR_TEST_FILES_DIR) + "/urdf/";
  std::vector<Case> out = {
      {test::data_path("robots/puma560.urdf"), ""},
      {urdf + "branching_tip.urdf", "a"},
      {urdf + "branching_tip.urdf", "tcp"},
      {urdf + "world_root.urdf", ""},
      {urdf + "fixed_chain.urdf", ""},
      {urdf + "continuous.urdf", ""},
      {urdf + "prismatic.urdf", ""},
      {urdf + "mimic_gripper.urdf", "tcp"},
      {urdf + "no_velocity.urdf", ""},
      {std::string(TELEAR_TEST_FILES_DIR) + "/robots/gripper_arm.yaml", ""},
  };
  // Every shipped robot file that wraps a URDF (the DH tables have `convention:` instead).
  std::vector<std::string> shipped;
  for (const auto& entry : fs::directory_iterator(test::data_path("robots"))) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".yaml" || name.find(".body.") != std::string::npos ||
        name.find(".marker.") != std::string::npos) {
      continue;
    }
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("\nurdf:") != std::string::npos || text.rfind("urdf:", 0) == 0) {
      shipped.push_back(entry.path().string());
    }
  }
  std::sort(shipped.begin(), shipped.end());
  for (const auto& s : shipped) out.push_back({s, ""});
  return out;
}

Eigen::Matrix4d to_matrix(const KDL::Frame& f) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T(r, c) = f.M(r, c);
    T(r, 3) = f.p(r);
  }
  return T;
}

TEST(UrdfAgainstKdl, ForwardKinematicsAgreesAtRandomConfigurations) {
  int checked = 0;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.path + " tip '" + c.tip + "'");
    auto d = load_robot_description({c.path, c.tip});
    ASSERT_TRUE(d) << d.error().message;
    KDL::Tree tree;
    ASSERT_TRUE(kdl_parser::treeFromString(d->urdf_text, tree));
    KDL::Chain chain;
    ASSERT_TRUE(tree.getChain(d->root_link, d->tip_link, chain));
    ASSERT_EQ(static_cast<int>(chain.getNrOfJoints()), d->model->dof());
    KDL::ChainFkSolverPos_recursive fk(chain);
    std::mt19937_64 rng(1234);
    double worst = 0.0;
    for (int k = 0; k < 1000; ++k) {
      const Eigen::VectorXd q = test::random_configuration(*d->model, rng);
      KDL::JntArray kq(chain.getNrOfJoints());
      for (int i = 0; i < q.size(); ++i) kq(static_cast<unsigned>(i)) = q[i];
      KDL::Frame tip;
      ASSERT_GE(fk.JntToCart(kq, tip), 0);
      worst = std::max(worst, test::max_abs_diff(tool_pose(*d->model, q).matrix(), to_matrix(tip)));
    }
    EXPECT_LT(worst, 1e-12);
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

}  // namespace
}  // namespace telear::core
