// The allowed-collision matrix stored with the robot file (geometry/allowed_collisions_file.hpp):
// the shipped URDF arms store exactly what sampling finds (the block `telear robot acm`
// prints, which scripts/generate_arms.py writes), a stored matrix is used as written, and the
// block loads back to the matrix it was written from.

#include "telear/geometry/allowed_collisions_file.hpp"
#include "test_util/test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <tuple>

#include "test_util/temp_dir.hpp"

namespace telear::geometry {
namespace {

using ::testing::HasSubstr;

const std::string kRobots = std::string(TELEAR_TEST_DATA_DIR) + "/robots";

using test::robot_description;

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::tuple<std::string, std::string, AllowedReason>> entries(
    const AllowedCollisionMatrix& m) {
  std::vector<std::tuple<std::string, std::string, AllowedReason>> out;
  for (const AllowedPair& p : m.pairs()) out.emplace_back(p.a, p.b, p.reason);
  return out;
}

// A robot file for the shipped arm `robot` (absolute URDF and package path) followed by
// `extra`.
std::string robot_file(const test_files::TempDir& dir, const std::string& robot,
                       const std::string& extra) {
  return dir.write(robot + "_acm.yaml", "urdf: " + kRobots + "/telear_" + robot + "/urdf/" + robot +
                                            ".urdf\npackage_paths: [" + kRobots + "]\ntip: tcp\n" +
                                            extra);
}

// The shipped arms store the matrix sampling finds, byte for byte the block the command
// prints; checking with them takes it as stored (no sampling at load).
TEST(AllowedCollisionsFile, TheShippedArmsStoreTheSampledMatrix) {
  for (const std::string robot : {"ur6", "arm7"}) {
    SCOPED_TRACE(robot);
    const core::RobotDescription d = robot_description(robot);
    ASSERT_TRUE(d.allowed_collisions) << robot << ".yaml stores no allowed_collisions:";
    auto sampled = sample_allowed_collisions(d);
    ASSERT_TRUE(sampled) << sampled.error().message;
    EXPECT_THAT(read(kRobots + "/" + robot + ".yaml"),
                HasSubstr(allowed_collisions_block(*sampled, robot, {})));
    auto checker = make_collision_checker(d, core::Workspace{});
    ASSERT_TRUE(checker) << checker.error().message;
    EXPECT_EQ(entries(checker->allowed()), entries(*sampled));
  }
}

// What the file says is what is checked: a pair that sampling leaves checked is allowed when
// the file says so, and nothing else is added but the adjacent pairs.
TEST(AllowedCollisionsFile, AStoredMatrixIsUsedAsWritten) {
  test_files::TempDir dir;
  const std::string path =
      robot_file(dir, "ur6", "allowed_collisions:\n  - [base_link, wrist_3_link]\n");
  auto d = core::load_robot_description({path, "", {}});
  ASSERT_TRUE(d) << d.error().message;
  auto checker = make_collision_checker(*d, core::Workspace{});
  ASSERT_TRUE(checker) << checker.error().message;
  auto robot = robot_collision_model(*d);
  ASSERT_TRUE(robot) << robot.error().message;
  AllowedCollisionMatrix expected = adjacent_collisions(*robot);
  expected.allow("base_link", "wrist_3_link", AllowedReason::kUser);
  EXPECT_EQ(entries(checker->allowed()), entries(expected));
  for (const CollisionPair& p : checker->pairs()) {
    if (p.other_body < 0) continue;
    const std::string a = checker->robot().bodies[static_cast<std::size_t>(p.body)].name;
    EXPECT_FALSE(a == "base_link" && checker->pair_other_name(p) == "wrist_3_link");
  }
}

// The block loads back to the matrix it was written from, every reason included; an empty
// matrix is `allowed_collisions: []` (stored: only the adjacent pairs, nothing sampled).
TEST(AllowedCollisionsFile, TheBlockRoundTripsThroughTheRobotFile) {
  test_files::TempDir dir;
  AllowedCollisionOptions options;
  options.samples = 50;
  options.allow_never = true;
  auto sampled = sample_allowed_collisions(robot_description("arm7"), {{}, options});
  ASSERT_TRUE(sampled) << sampled.error().message;
  // One never pair written as constant (arm7 has no pair at a constant distance), one as user:
  // the block carries every reason.
  AllowedCollisionMatrix m;
  for (const AllowedPair& p : sampled->pairs()) {
    const bool as_constant = p.a == "link0" && p.b == "link2";
    ASSERT_TRUE(!as_constant || p.reason == AllowedReason::kNever);
    m.allow(p.a, p.b, as_constant ? AllowedReason::kConstant : p.reason);
  }
  m.allow("link0", "hand", AllowedReason::kUser);
  const std::string block = allowed_collisions_block(m, "arm7", options);
  EXPECT_THAT(block, HasSubstr("# 50 random configurations within the joint limits (seed 13), "
                               "gripper at 0.5, constant-distance pairs (within 0.1 mm) allowed, "
                               "never-in-contact pairs allowed.\n"
                               "allowed_collisions:\n  - ["));
  EXPECT_THAT(block, HasSubstr("\n  - [link0, link2, constant]\n"));
  auto d = core::load_robot_description({robot_file(dir, "arm7", block), "", {}});
  ASSERT_TRUE(d) << d.error().message;
  auto checker = make_collision_checker(*d, core::Workspace{});
  ASSERT_TRUE(checker) << checker.error().message;
  EXPECT_EQ(entries(checker->allowed()), entries(m));
  bool never = false;
  for (const AllowedPair& p : m.pairs()) never = never || p.reason == AllowedReason::kNever;
  EXPECT_TRUE(never);
  EXPECT_TRUE(checker->allowed().allowed("link2", "link0"));

  const std::string empty = allowed_collisions_block(AllowedCollisionMatrix{}, "arm7", {});
  EXPECT_THAT(empty, HasSubstr("\nallowed_collisions: []\n"));
  auto bare = core::load_robot_description({robot_file(dir, "arm7", empty), "", {}});
  ASSERT_TRUE(bare) << bare.error().message;
  ASSERT_TRUE(bare->allowed_collisions);
  EXPECT_TRUE(bare->allowed_collisions->empty());
  auto robot = robot_collision_model(*bare);
  ASSERT_TRUE(robot) << robot.error().message;
  auto adjacent_only = make_collision_checker(*bare, core::Workspace{});
  ASSERT_TRUE(adjacent_only) << adjacent_only.error().message;
  EXPECT_EQ(entries(adjacent_only->allowed()), entries(adjacent_collisions(*robot)));
}

TEST(AllowedCollisionsFile, SamplingRefusesBadOptions) {
  AllowedCollisionOptions options;
  options.samples = 0;
  auto bad = sample_allowed_collisions(robot_description("ur6"), {{}, options});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "allowed collisions: samples must be at least 1, got 0");
}

}  // namespace
}  // namespace telear::geometry
