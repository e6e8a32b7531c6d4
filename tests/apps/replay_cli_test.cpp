// `telear replay` from a shell (issue 22): a console session recorded with --record, its view
// written headless at a time, and the command's bad input.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"
#include "telear/render/image_io.hpp"

namespace telear {
namespace {

namespace fs = std::filesystem;
using test::run_telear;
using ::testing::HasSubstr;

TEST(ReplayCli, ARecordedConsoleSessionIsDrawnAtTheGivenTime) {
  const test_files::TempDir tmp("replay-cli");
  const std::string recording = tmp.file("session.mcap"), shot = tmp.file("at.png");
  const std::string script = tmp.file("ghost.txt");
  std::ofstream(script) << "wait-until in-control 20\nwait-until video 20\n"
                           "ghost joint 2 +10deg\nwait 0.5\n";
  const auto recorded = run_telear(
      "console --headless --resolution 320x240 --size 800x500 "
      "--script " +
      script + " --record " + recording);
  ASSERT_EQ(recorded.exit_code, 0) << recorded.out << recorded.err;

  const auto replayed = run_telear("replay " + recording +
                                   " --headless --size 800x500 --at 0.6 --screenshot " + shot);
  ASSERT_EQ(replayed.exit_code, 0) << replayed.out << replayed.err;
  EXPECT_THAT(replayed.out, HasSubstr("stereo frames"));
  EXPECT_THAT(replayed.out, HasSubstr("telear replay: wrote " + shot + " (at 0.60 s)"));
  auto image = render::read_image(shot);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->width, 800);
  EXPECT_EQ(image->height, 500);
  // The video fills the view: not the empty window's flat colour.
  int distinct = 0;
  for (int x = 20; x < 780; x += 20) distinct += image->at(x, 150, 0) != image->at(x + 10, 150, 0);
  EXPECT_GT(distinct, 5);

  // Another arm than the recorded one is refused, naming both joint counts.
  const auto arm7 = run_telear("replay " + recording + " --headless --robot arm7");
  EXPECT_EQ(arm7.exit_code, 2);
  EXPECT_THAT(arm7.err,
              HasSubstr("telear replay: robot 'arm7' has 7 joints, the recording 6 (give the "
                        "recorded arm with --robot)"));
}

TEST(ReplayCli, BadInputIsOneLineNamingTheProblem) {
  const test_files::TempDir tmp("replay-cli-bad");
  const auto missing = run_telear("replay " + tmp.file("none.mcap") + " --headless");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("telear replay: "));
  EXPECT_THAT(missing.err, HasSubstr("none.mcap"));
  const std::string text = tmp.file("text.mcap");
  std::ofstream(text) << "hello";
  const auto not_mcap = run_telear("replay " + text + " --headless");
  EXPECT_EQ(not_mcap.exit_code, 2);
  EXPECT_THAT(not_mcap.err, HasSubstr(text));
  const auto speed = run_telear("replay " + text + " --headless --speed 0");
  EXPECT_EQ(speed.exit_code, 2);
  EXPECT_EQ(speed.err, "telear replay: speed 0: within 1/16 .. 16\n");
  const auto no_file = run_telear("replay --headless");
  EXPECT_EQ(no_file.exit_code, 2);
  EXPECT_THAT(no_file.err, HasSubstr("telear replay: "));
}

}  // namespace
}  // namespace telear
