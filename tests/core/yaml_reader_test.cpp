// core/yaml_reader: loading YAML and reading numbers answer with Results (no exception), and
// the messages name the file, the line and the key.

#include "telear/core/yaml_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "test_util/temp_dir.hpp"

namespace telear::core {
namespace {

TEST(LoadYaml, ParsesADocument) {
  const auto root = load_yaml("a: 1\nb: [2, 3]\n", "file 'x.yaml': ");
  ASSERT_TRUE(root) << root.error().message;
  EXPECT_TRUE(root->IsMap());
  EXPECT_EQ((*root)["b"].size(), 2u);
}

TEST(LoadYaml, NamesTheFileAndTheLineOfASyntaxError) {
  const auto root = load_yaml("a: 1\nb: [2, 3\n", "file 'x.yaml': ");
  ASSERT_FALSE(root);
  EXPECT_EQ(root.error().message.rfind("file 'x.yaml': not valid YAML at line ", 0), 0u)
      << root.error().message;
}

TEST(LoadYamlFile, ReadsAFileOrSaysItCannot) {
  test_files::TempDir tmp("yaml_reader");
  const std::string path = tmp.write("reader.yaml", "k: 2.5\n");
  const auto root = load_yaml_file(path, "");
  ASSERT_TRUE(root) << root.error().message;
  EXPECT_EQ((*root)["k"].as<double>(), 2.5);
  EXPECT_EQ(load_yaml_file("/nonexistent/f.yaml", "file '/nonexistent/f.yaml': ").error().message,
            "file '/nonexistent/f.yaml': cannot be read");
}

TEST(YamlNumber, ReadsFiniteNumbersAndSaysWhyNot) {
  const YAML::Node root = YAML::Load("a: 1.5\nb: x\nc: .inf\nd: [1]\n");
  const auto a = yaml_number(root["a"], "a");
  ASSERT_TRUE(a);
  EXPECT_EQ(*a, 1.5);
  EXPECT_EQ(yaml_number(root["b"], "b").error().message, "b: must be a number, got 'x'");
  EXPECT_EQ(yaml_number(root["c"], "c").error().message, "c: must be finite, got .inf");
  EXPECT_EQ(yaml_number(root["d"], "joint 1 d_m", " ").error().message,
            "joint 1 d_m must be a number");
}

TEST(YamlNumbers, ReadsAListNamingTheBadItem) {
  const YAML::Node root = YAML::Load("q: [0, 1.5, -2]\nbad: [0, y]\nscalar: 3\n");
  const auto q = yaml_numbers(root["q"], "q");
  ASSERT_TRUE(q);
  EXPECT_EQ(*q, (std::vector<double>{0, 1.5, -2}));
  EXPECT_EQ(yaml_numbers(root["bad"], "bad").error().message, "bad[1]: must be a number, got 'y'");
  EXPECT_EQ(yaml_numbers(root["scalar"], "scalar").error().message,
            "scalar: must be a list of numbers");
}

TEST(YamlPose, ReadsXyzAndRpyAndNamesTheBadField) {
  const YAML::Node root = YAML::Load(
      "p: {xyz: [1, 2, 3], rpy: [0, 0, 1.5707963267948966]}\n"
      "no_rpy: {xyz: [1, 2, 3]}\n"
      "short: {xyz: [1, 2]}\n"
      "extra: {xyz: [1, 2, 3], scale: 2}\n"
      "bad_angle: {xyz: [1, 2, 3], rpy: [0, x, 0]}\n"
      "no_xyz: {rpy: [0, 0, 0]}\n");
  const auto p = yaml_pose(root["p"], "p");
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_TRUE(p->translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  // Yaw of 90 degrees: x turns onto y.
  EXPECT_TRUE((p->linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  const auto no_rpy = yaml_pose(root["no_rpy"], "no_rpy");
  ASSERT_TRUE(no_rpy);
  EXPECT_TRUE(no_rpy->linear().isIdentity());
  EXPECT_EQ(yaml_pose(root["short"], "short").error().message,
            "short.xyz must be a list of 3 numbers");
  EXPECT_EQ(yaml_pose(root["extra"], "extra").error().message,
            "extra: unknown key 'scale' (expected xyz, rpy)");
  EXPECT_EQ(yaml_pose(root["bad_angle"], "bad_angle").error().message,
            "bad_angle.rpy[1]: must be a number, got 'x'");
  EXPECT_EQ(yaml_pose(root["no_xyz"], "no_xyz").error().message, "no_xyz.xyz: missing");
}

}  // namespace
}  // namespace telear::core
