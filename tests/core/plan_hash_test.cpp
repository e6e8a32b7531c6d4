// plan_hash (telear/core/plan_hash.hpp): determinism, sensitivity, and golden values.

#include "telear/core/plan_hash.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>

#include "telear/core/angles.hpp"
#include "telear/core/sha256.hpp"
#include "telear/core/trajectory.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;
using ::testing::MatchesRegex;

using test::deg;

// A pick-and-place on the PUMA written out in full (no random numbers, so that the golden
// values below depend on nothing but telear's own arithmetic): approach, via points around
// the part, a dwell while the gripper closes, a lift and a place.
std::vector<JointWaypoint> pick_and_place() {
  std::vector<JointWaypoint> w;
  w.push_back({deg({0, -30, 45, 0, 30, 0}), 0.0, 1.0});
  w.push_back({deg({20, -10, 60, 10, 40, -20}), 0.0, std::nullopt, true});
  w.push_back({deg({35, 5, 75, 15, 50, -30}), 0.0, std::nullopt, true});
  w.push_back({deg({40, 10, 80, 15, 55, -35})});
  w.push_back({deg({40, 10, 80, 15, 55, -35}), 0.8, 0.0});  // grasp
  w.push_back({deg({30, -5, 60, 5, 45, -10}), 0.0, std::nullopt, true});
  w.push_back({deg({-10, -20, 50, -5, 35, 20}), 1.2, std::nullopt, true});
  w.push_back({deg({-30, -10, 70, -10, 50, 30}), 0.0, 1.0});
  return w;
}

// Along a line of the tool and back along it (Cartesian segments), then a joint-space move.
std::vector<JointWaypoint> line_and_back() {
  std::vector<JointWaypoint> w;
  w.push_back({deg({0, -30, 45, 0, 30, 0}), 0.0, 1.0});
  w.push_back({deg({10, -20, 55, 5, 35, -5})});
  w.back().cartesian = true;
  w.push_back({deg({0, -30, 45, 0, 30, 0}), 0.0, 0.0, true});
  w.back().cartesian = true;
  w.push_back({deg({-20, -30, 45, 0, 30, 0})});
  return w;
}

class PlanHash : public ::testing::Test {
 protected:
  RobotModelPtr model = test::puma560();
  std::string hash_of(std::vector<JointWaypoint> waypoints, const TrajectoryOptions& options = {}) {
    auto trajectory = Trajectory::create(*model, std::move(waypoints), options);
    EXPECT_TRUE(trajectory.ok()) << trajectory.error().message;
    if (!trajectory) return {};
    auto hash = plan_hash(*trajectory);
    EXPECT_TRUE(hash.ok()) << hash.error().message;
    return hash.ok() ? *hash : std::string();
  }
};

TEST(Sha256, MatchesTheStandardsTestVectors) {
  // FIPS 180-2, appendix B.1, and the empty string.
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST_F(PlanHash, IsLowercaseHexAndTheSameEveryTime) {
  const std::string first = hash_of(pick_and_place());
  EXPECT_THAT(first, MatchesRegex("[0-9a-f]{64}"));
  EXPECT_EQ(hash_of(pick_and_place()), first);
  const Trajectory traj = *Trajectory::create(*model, pick_and_place());
  EXPECT_EQ(*plan_hash(traj), first);
  EXPECT_EQ(*plan_hash(traj), first);  // hashing does not change the trajectory
  const Trajectory copy = traj;
  EXPECT_EQ(*plan_hash(copy), first);
}

TEST_F(PlanHash, GoldenValuesGuardCrossMachineDeterminism) {
  // These constants are the hashes a reference build (Debian 12, GCC 12, x86-64, Release)
  // computed. The time parameterization promises bit-identical results in any process on any
  // x86-64 machine (trajectory.hpp, "Determinism"); the server executes a plan only when its
  // own hash equals the client's, so a build that drifts by one bit (a fused multiply-add, a
  // reordered sum, a changed constant) must fail here rather than refuse every plan in the
  // field. A deliberate change to the algorithm changes kTrajectoryAlgorithm and these values.
  EXPECT_EQ(kTrajectoryAlgorithm, "telear-blend-2");
  EXPECT_EQ(hash_of(pick_and_place()),
            "f9d2e51c1b24bc16c2c69dc9bf1ae9fb400c7ed16eb11a0d42fb67f1f77bfd4a");
  std::vector<JointWaypoint> stops = pick_and_place();
  for (auto& w : stops) w.via = false;
  EXPECT_EQ(hash_of(stops, {.velocity_scale = 0.5, .acceleration_scale = 0.25}),
            "4e551b74d45b1a6b96e3e6fed304466284b639427ccd9f87d21c31b2c1a628cc");
  // A Cartesian segment: its expansion (IK at every step, libm's trigonometry inside the PUMA's
  // closed form, rounded to kCartesianJointGrid) is hashed with it.
  EXPECT_EQ(hash_of(line_and_back()),
            "37dcda482a9edead28c4cabd5306af233cff772fff8caef24f8d380f4bfca8b7");
}

TEST_F(PlanHash, JointPlansAreTimedAsByTelearBlend1) {
  // telear-blend-2 added Cartesian segments only: a plan without them has telear-blend-1's
  // bytes but for the name (the golden value of telear-blend-1 below).
  std::string bytes = *canonical_plan_bytes(*Trajectory::create(*model, pick_and_place()));
  ASSERT_EQ(bytes.substr(4, 14), "telear-blend-2");
  bytes.replace(4, 14, "telear-blend-1");
  EXPECT_EQ(sha256_hex(bytes), "a61a5df8d53dbe038bd29318104670fb54f001bcb1d4103fb872a7a93879ea6c");
}

TEST_F(PlanHash, ChangesWithEveryParameter) {
  const std::string base = hash_of(pick_and_place());
  auto changed = [&](auto edit, const TrajectoryOptions& options = {}) {
    std::vector<JointWaypoint> w = pick_and_place();
    edit(w);
    return hash_of(w, options);
  };
  // A nanoradian on one joint of one waypoint.
  EXPECT_NE(changed([](auto& w) { w[2].q[3] += 1e-9; }), base);
  EXPECT_NE(changed([](auto& w) { w[5].q[0] -= 1e-9; }), base);
  EXPECT_NE(changed([](auto& w) { w[1].via = false; }), base);
  EXPECT_NE(changed([](auto& w) { w[3].via = true; }), base);  // a stop before a dwell: flag only
  EXPECT_NE(changed([](auto& w) { w[4].cartesian = true; }), base);  // a dwell: flag only
  EXPECT_NE(changed([](auto& w) { w[4].min_duration = 0.81; }), base);
  EXPECT_NE(changed([](auto& w) { w[4].gripper = 0.01; }), base);
  EXPECT_NE(changed([](auto& w) { w[3].gripper = 0.0; }), base);
  EXPECT_NE(changed([](auto&) {}, {.velocity_scale = 0.999}), base);
  EXPECT_NE(changed([](auto&) {}, {.acceleration_scale = 0.999}), base);
  EXPECT_NE(changed([](auto& w) { w.pop_back(); }), base);
  EXPECT_EQ(changed([](auto&) {}), base);
}

TEST_F(PlanHash, ChangesWithTheRobotsLimits) {
  RobotModel::Description d;
  d.name = model->name();
  d.joints = model->joints();
  d.T_flange_tool = model->T_flange_tool();
  d.joints[2].limits.max_velocity *= 1.0 + 1e-12;
  const RobotModel slower = *RobotModel::create(std::move(d));
  const Trajectory a = *Trajectory::create(*model, pick_and_place());
  const Trajectory b = *Trajectory::create(slower, pick_and_place());
  EXPECT_NE(*plan_hash(a), *plan_hash(b));
}

TEST_F(PlanHash, CanonicalBytesFollowTheDocumentedLayout) {
  const Trajectory traj = *Trajectory::create(*model, pick_and_place());
  const std::string bytes = *canonical_plan_bytes(traj);
  // u32 14, "telear-blend-2", u32 6 (little-endian).
  ASSERT_GE(bytes.size(), 22u);
  EXPECT_EQ(bytes.substr(0, 4), std::string("\x0e\x00\x00\x00", 4));
  EXPECT_EQ(bytes.substr(4, 14), "telear-blend-2");
  EXPECT_EQ(bytes.substr(18, 4), std::string("\x06\x00\x00\x00", 4));
  double v0 = 0.0;
  std::memcpy(&v0, bytes.data() + 22, 8);  // x86-64 is little-endian
  EXPECT_EQ(v0, model->max_velocities()[0]);
  const size_t n = traj.waypoints().size();
  const auto grid = static_cast<size_t>(std::floor(traj.duration() * 100.0));
  const size_t samples = grid + 1 + (static_cast<double>(grid) / 100.0 < traj.duration() ? 1 : 0);
  const size_t events = traj.gripper_events().size();
  EXPECT_EQ(bytes.size(), 4 + 14 + 4 + 6 * 16 + 16 + 4 + n * (6 * 8 + 1 + 8 + 1 + 8) + 8 + 4 +
                              samples * 6 * 8 + 4 + events * 16);
  EXPECT_EQ(sha256_hex(bytes), *plan_hash(traj));
}

TEST_F(PlanHash, RefusesAPlanTooLongToHash) {
  std::vector<JointWaypoint> w{{deg({0, 0, 0, 0, 0, 0})}};
  for (int i = 0; i < 3; ++i) w.push_back({deg({0, 0, 0, 0, 0, 0}), 400.0});
  const Trajectory traj = *Trajectory::create(*model, w);
  const auto hash = plan_hash(traj);
  ASSERT_FALSE(hash.ok());
  EXPECT_EQ(hash.error().message,
            "the 1200 s trajectory is too long to hash: at 100 Hz it needs 120002 samples, more "
            "than the maximum of 100000");
}

}  // namespace
}  // namespace telear::core
