// The simulated rig as a vision source (sim/sim_rig_source.hpp): frames rendered on headless
// EGL for the scene state the caller provides. (With the vision server's other sources in
// tests/net; kept here so the net tests, and their AddressSanitizer build, need no renderer.)
#include <gtest/gtest.h>

#include <optional>

#include "telear/sim/sim_rig_source.hpp"
#include "test_util/test_util.hpp"

namespace telear::sim {
namespace {

TEST(SimRigSource, FramesFollowTheProvidedState) {
  int calls = 0;
  SimRigSourceOptions options;
  options.rig = test::data_path("rigs/puma560_rig.yaml");
  options.fps = 1000;
  options.supersample = 1;
  options.noise_sigma = 0;
  Eigen::VectorXd q_a = Eigen::VectorXd::Zero(6), q_b = Eigen::VectorXd::Zero(6);
  q_b << 0.6, -0.4, 0.3, 0.2, 0.5, -0.3;
  options.scene_state = [&]() -> std::optional<vision::SceneState> {
    ++calls;
    return vision::SceneState{calls == 1 ? q_a : q_b, 0.5, 1234};
  };
  auto source = SimRigSource::create(options);
  ASSERT_TRUE(source) << source.error().message;
  EXPECT_EQ((*source)->name(), "sim");
  EXPECT_EQ((*source)->width(), 640);
  EXPECT_EQ((*source)->height(), 480);
  auto prepared = (*source)->prepare();
  // Like the GL tests: a machine without headless EGL fails here, it does not skip.
  ASSERT_TRUE(prepared) << prepared.error().message;
  auto first = (*source)->capture();
  auto second = (*source)->capture();
  ASSERT_TRUE(first && second);
  ASSERT_TRUE(first->scene && second->scene);
  EXPECT_TRUE(first->scene->q.isApprox(q_a));
  EXPECT_TRUE(second->scene->q.isApprox(q_b));
  EXPECT_EQ(second->scene->state_ns, 1234);
  EXPECT_EQ(first->left.width, 640);
  EXPECT_EQ(first->left.height, 480);
  EXPECT_EQ(first->left.channels, 3);
  // The arm moved: the picture changed (noise is off, so only the arm can change it).
  EXPECT_NE(first->left.pixels, second->left.pixels);
  EXPECT_NE(first->left.pixels, first->right.pixels);  // two viewpoints
  (*source)->release();
}

}  // namespace
}  // namespace telear::sim
