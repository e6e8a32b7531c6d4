// `telear sim frame` end to end: the simulated scene at a configuration, both eyes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "cli_runner.hpp"
#include "test_util/temp_dir.hpp"

namespace telear {
namespace {

using test::run_telear;
using ::testing::HasSubstr;

TEST(SimFrameCli, WritesBothEyesOfTheSceneAtAConfiguration) {
  test_files::TempDir tmp("sim_frame");
  const std::string prefix = tmp.file("frame");
  const auto r = run_telear("sim frame --rig " + std::string(TELEAR_TEST_DATA_DIR) +
                            "/rigs/puma560_rig.yaml --q qr -o " + prefix);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* eye : {"_left.png", "_right.png"}) {
    const std::string path = prefix + eye;
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    EXPECT_GT(std::filesystem::file_size(path), 10000u) << path;  // a real scene, not blank
    EXPECT_THAT(r.out, HasSubstr("wrote " + path));
  }
}

// The default rig comes from core::data_directory(), not from a path relative to the working
// directory: `telear sim frame` works from anywhere without TELEAR_DATA_DIR.
TEST(SimFrameCli, DefaultRigIsFoundFromAnyWorkingDirectory) {
  test_files::TempDir tmp("sim_frame_cwd");
  const std::filesystem::path dir = tmp.path();
  const std::string command = "cd '" + dir.string() + "' && env -u TELEAR_DATA_DIR " +
                              std::string(TELEAR_BINARY) +
                              " sim frame --q qr -o frame > out.txt 2> err.txt";
  const int status = std::system(command.c_str());
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0) << test::slurp(dir / "err.txt");
  for (const char* eye : {"frame_left.png", "frame_right.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / eye)) << (dir / eye);
  }
}

TEST(SimFrameCli, BadInputIsOneLineAndWritesNothing) {
  test_files::TempDir tmp("sim_frame_bad");
  const std::string prefix = tmp.file("frame");
  const std::string rig = " --rig " + std::string(TELEAR_TEST_DATA_DIR) + "/rigs/puma560_rig.yaml";
  const auto wrong_count = run_telear("sim frame" + rig + " --q 0,0,0 -o " + prefix);
  EXPECT_EQ(wrong_count.exit_code, 2);
  // The same message as every command's --q (core/joint_values.hpp).
  EXPECT_EQ(wrong_count.err,
            "telear sim frame: --q: expected 6 numbers, got 3 (robot 'puma560' has 6 joints)\n");
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
