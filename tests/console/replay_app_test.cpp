// `telear replay` (issue 22): a console session recorded with --record, replayed headless,
// draws the same view pixels as the live console did, from the recorded frame and state.

#include "telear/console/replay_app.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/console_command.hpp"
#include "scripted_console.hpp"
#include "telear/console/console_app.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::console {
namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

// What the live console drew at one display frame.
struct LiveSample {
  core::Image view;        // the AR view (both eyes composed)
  core::Image video_left;  // the decoded frame it drew on
  Eigen::VectorXd ghost_q;
};

// Pixels that differ by more than `tolerance` in any channel.
int differing_pixels(const core::Image& a, const core::Image& b, int tolerance) {
  int n = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > tolerance) {
          ++n;
          break;
        }
      }
    }
  }
  return n;
}

TEST(ReplayApp, AReplayedSessionDrawsTheLiveViewsPixels) {
  test_files::TempDir tmp("replay");
  const fs::path dir = tmp.path();
  const std::string recording = (dir / "session.mcap").string();
  const std::string script = (dir / "ghost.txt").string();
  // The ghost moves, the robot stays: each sample's ghost pose is its own.
  std::ofstream(script) << "wait-until connected 30\n"
                           "wait-until in-control 10\n"
                           "wait-until video 20\n"
                           "wait 0.3\n"
                           "ghost joint 1 +4deg\nwait 0.15\n"
                           "ghost joint 2 +5deg\nwait 0.15\n"
                           "ghost joint 3 -6deg\nwait 0.15\n"
                           "ghost joint 1 -9deg\nwait 0.15\n"
                           "ghost gripper close\nwait 0.15\n"
                           "ghost joint 5 +20deg\nwait 0.15\n"
                           "ghost joint 2 -8deg\nwait 0.3\n";
  ConsoleOptions options = telear::test::scripted_headless_console(script, 800, 500);
  options.frames = 0;  // the script's end ends it
  options.record = recording;
  std::ostringstream log;
  std::vector<LiveSample> live;
  {
    auto created = ConsoleApp::create(options, log);
    ASSERT_TRUE(created) << created.error().message;
    ConsoleApp& app = **created;
    const auto start = Clock::now();
    int fresh_ar = 0;  // consecutive frames drawn in AR on fresh video
    while (app.frame()) {
      const session::SessionView& v = app.session().view();
      const bool fresh =
          v.frame && !v.display.frame_stale && v.display.mode == session::DisplayMode::kAR;
      fresh_ar = fresh ? fresh_ar + 1 : 0;
      // Not the first frames after the switch to AR: the switch's event is logged during the
      // update that draws the first AR frame, which a replay at the same time may not see yet.
      if (fresh_ar >= 3 && !app.script().finished() && live.size() < 40) {
        live.push_back({app.read_view_image(), v.frame->left, v.ghost_q});
      }
      ASSERT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 60.0) << log.str();
    }
    ASSERT_EQ(app.script().failures(), 0) << log.str();
    ASSERT_TRUE(app.stop_recording());
  }
  // A loaded machine draws ~10 frames per second: at least a few fresh AR frames.
  ASSERT_GE(live.size(), 3u) << log.str();

  ReplayOptions replay_options;
  replay_options.path = recording;
  replay_options.headless = true;
  replay_options.width = 640;
  replay_options.height = 400;
  auto replay = ReplayApp::create(replay_options, log);
  ASSERT_TRUE(replay) << replay.error().message;
  ReplayApp& app = **replay;
  const record::RecordingSeries& series = app.playback().series();

  // Each live sample's moment in the recording: the ghost message recorded for its display
  // frame (the same pose). The replay shows the frame the live view showed (the newest decoded,
  // from the recorded latency messages) and draws the same image.
  int compared = 0;
  for (const LiveSample& sample : live) {
    const record::JointSample* moment = nullptr;
    for (const record::JointSample& ghost : series.ghost.samples) {
      if (ghost.position == sample.ghost_q) {
        app.seek(ghost.t);
        const record::PlaybackFrame* shown =
            *const_cast<record::RecordingPlayback&>(app.playback()).frame(*app.moment().frame);
        if (shown->left.pixels == sample.video_left.pixels) {
          moment = &ghost;
          break;
        }
      }
    }
    ASSERT_NE(moment, nullptr) << "no recorded moment shows sample " << compared << "'s frame";
    ASSERT_EQ(app.moment().ghost->position, sample.ghost_q);
    auto image = app.render_view();
    ASSERT_TRUE(image) << image.error().message;
    ASSERT_EQ(image->width, sample.view.width);
    ASSERT_EQ(image->height, sample.view.height);
    EXPECT_EQ(differing_pixels(*image, sample.view, 0), 0) << "at " << moment->t << " s";
    ++compared;
  }
  EXPECT_EQ(compared, static_cast<int>(live.size()));
}

TEST(ReplayApp, ARecordingThatDoesNotOpenIsAnErrorNamingIt) {
  test_files::TempDir tmp("replay-bad");
  const std::string bad = (tmp.path() / "notes.mcap").string();
  std::ofstream(bad) << "not a recording";
  std::ostringstream log;
  ReplayOptions options;
  options.headless = true;
  options.path = bad;
  auto app = ReplayApp::create(options, log);
  ASSERT_FALSE(app);
  EXPECT_THAT(app.error().message, HasSubstr(bad));
  options.path = (tmp.path() / "missing.mcap").string();
  app = ReplayApp::create(options, log);
  ASSERT_FALSE(app);
  EXPECT_THAT(app.error().message, HasSubstr("missing.mcap"));
  options.path = bad;
  options.speed = 40;
  app = ReplayApp::create(options, log);
  ASSERT_FALSE(app);
  EXPECT_EQ(app.error().message, "speed 40: within 1/16 .. 16");
}

}  // namespace
}  // namespace telear::console
