// `telear sim frame` end to end: the simulated scene at a configuration, both eyes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "cli_runner.hpp"

namespace telear {
namespace {

using test::run_telear;
using ::testing::HasSubstr;

TEST(SimFrameCli, WritesBothEyesOfTheSceneAtAConfiguration) {
  const std::string prefix = ::testing::TempDir() + "sim_frame_" + std::to_string(::getpid());
  const auto r = run_telear("sim frame --rig " + std::string(TELEAR_TEST_DATA_DIR) +
                            "/rigs/puma560_rig.yaml --q qr -o " + prefix);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* eye : {"_left.png", "_right.png"}) {
    const std::string path = prefix + eye;
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    EXPECT_GT(std::filesystem::file_size(path), 10000u) << path;  // a real scene, not blank
    EXPECT_THAT(r.out, HasSubstr("wrote " + path));
    std::filesystem::remove(path);
  }
}

TEST(SimFrameCli, BadInputIsOneLineAndWritesNothing) {
  const std::string prefix = ::testing::TempDir() + "sim_frame_bad_" + std::to_string(::getpid());
  const std::string rig = " --rig " + std::string(TELEAR_TEST_DATA_DIR) + "/rigs/puma560_rig.yaml";
  const auto wrong_count = run_telear("sim frame" + rig + " --q 0,0,0 -o " + prefix);
  EXPECT_EQ(wrong_count.exit_code, 2);
  EXPECT_EQ(wrong_count.err, "telear sim frame: --q: expected 6 numbers, got 3\n");
  const auto gripper = run_telear("sim frame" + rig + " --gripper -1 -o " + prefix);
  EXPECT_EQ(gripper.exit_code, 2);
  EXPECT_EQ(gripper.err, "telear sim frame: --gripper must be an opening between 0 and 0.2 m\n");
  const auto no_rig = run_telear("sim frame --rig /nonexistent/rig.yaml -o " + prefix);
  EXPECT_EQ(no_rig.exit_code, 2);
  EXPECT_THAT(no_rig.err, HasSubstr("/nonexistent/rig.yaml"));
  EXPECT_FALSE(std::filesystem::exists(prefix + "_left.png"));
}

}  // namespace
}  // namespace telear
