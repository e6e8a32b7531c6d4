// RecordingPlayback (telear replay's reader): what the view had at a time -- the newest frame
// received, the ghost the view drew, the AR/VR mode -- from a recording written by the real
// SessionRecorder with decodable JPEGs and a calibration, without servers.

#include "telear/record/recording_playback.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "telear/core/robot_description.hpp"
#include "telear/net/jpeg_codec.hpp"
#include "telear/record/session_recorder.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::record {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr std::int64_t kMs = 1'000'000;

core::Image solid(int width, int height, std::uint8_t grey) {
  core::Image image(width, height, 3);
  image.pixels.assign(image.pixels.size(), grey);
  return image;
}

vision::CameraModel camera(double x) {
  vision::CameraModel c;
  c.width = 64;
  c.height = 48;
  c.fx = c.fy = 60.0;
  c.cx = 31.5;
  c.cy = 23.5;
  c.T_cam_base.translation() = Eigen::Vector3d(x, 0.0, 2.0);
  return c;
}

struct Written {
  std::string path;
  std::int64_t base_ns = 0;
};

// Three frames (grey 40, 120, 200) received at base + 100, 200, 300 ms and decoded (shown) 30 ms
// later; the view's ghost at base + 50 ms (q = 0.1) and + 250 ms (q = 0.2); VR from + 150 ms to
// + 280 ms.
Result<Written> write_recording(const fs::path& dir, bool with_cameras) {
  auto description = core::load_robot_description({"puma560"});
  if (!description) return description.error();
  RecordedSetup setup;
  setup.robot.model_name = "puma560";
  setup.robot.urdf = core::urdf_text_for_clients(*description);
  for (const core::Joint& j : description->model->joints()) setup.robot.joints.push_back({j.name});
  if (with_cameras) setup.cameras = vision::StereoCameraModel{camera(0.0), camera(0.1)};
  SessionRecorderOptions options;
  options.path = (dir / (with_cameras ? "view.mcap" : "no-cameras.mcap")).string();
  options.ghost_from_state_stream = false;
  options.metadata["robot_spec"] = "puma560";
  auto recorder = SessionRecorder::create(options, setup);
  if (!recorder) return recorder.error();
  const std::int64_t base = core::monotonic_ns();
  net::JpegEncoder encoder;
  std::vector<std::string> jpegs;
  for (std::uint8_t grey : {40, 120, 200}) {
    auto jpeg = encoder.encode(solid(64, 48, grey), 95);
    if (!jpeg) return jpeg.error();
    jpegs.push_back(*jpeg);
  }
  (*recorder)->add_ghost(Eigen::VectorXd::Constant(6, 0.1), 1.0, base + 50 * kMs);
  for (int i = 0; i < 3; ++i) {
    if (i == 1)
      (*recorder)->add_plan_event(PlanEventKind::kDisplayMode, "vr: video late", "", "",
                                  base + 150 * kMs);
    if (i == 2) (*recorder)->add_ghost(Eigen::VectorXd::Constant(6, 0.2), 0.0, base + 250 * kMs);
    if (i == 2)
      (*recorder)->add_plan_event(PlanEventKind::kDisplayMode, "ar: video fresh", "", "",
                                  base + 280 * kMs);
    net::ReceivedStereoFrame f;
    f.frame_id = static_cast<std::uint64_t>(i + 1);
    f.jpeg_left = &jpegs[static_cast<std::size_t>(i)];
    f.jpeg_right = &jpegs[static_cast<std::size_t>(2 - i)];
    f.receive_ns = base + (i + 1) * 100 * kMs;
    f.capture_ns_left = f.capture_ns_right = f.receive_ns - 10 * kMs;
    (*recorder)->add_frame(f);
    net::DecodedStereoFrame shown;
    shown.frame_id = f.frame_id;
    shown.capture_ns_left = f.capture_ns_left;
    shown.capture_ns_right = f.capture_ns_right;
    shown.decoded_ns = f.receive_ns + 30 * kMs;
    (*recorder)->add_latency(shown);
  }
  auto closed = (*recorder)->close();
  if (!closed) return closed.error();
  return Written{options.path, base};
}

TEST(RecordingPlayback, AtATimeTheViewHasTheNewestFrameGhostAndMode) {
  test_files::TempDir tmp("playback");
  auto written = write_recording(tmp.path(), true);
  ASSERT_TRUE(written) << written.error().message;
  auto playback = RecordingPlayback::open(written->path);
  ASSERT_TRUE(playback) << playback.error().message;
  EXPECT_EQ(playback->robot_spec(), "puma560");
  EXPECT_EQ(playback->cameras().left.width, 64);
  EXPECT_NEAR(playback->cameras().right.T_cam_base.translation().x(), 0.1, 1e-12);
  ASSERT_EQ(playback->series().frames[0].size(), 3u);
  // The recording starts at its first message: the ghost at base + 50 ms.
  const double frame0 = playback->series().frames[0][0].t;
  EXPECT_NEAR(frame0, 0.050, 1e-9);

  PlaybackMoment m = playback->at(0.0);  // the first ghost, no frame yet, AR
  EXPECT_FALSE(m.frame);
  ASSERT_TRUE(m.ghost);
  EXPECT_DOUBLE_EQ(m.ghost->position[0], 0.1);
  EXPECT_FALSE(m.vr);

  m = playback->at(frame0 + 0.040);  // base + 140 ms: frame 1 decoded (130)
  ASSERT_TRUE(m.frame);
  EXPECT_EQ(*m.frame, 0u);
  EXPECT_FALSE(m.vr);

  m = playback->at(frame0 + 0.120);  // base + 220 ms: frame 2 arrived (200), not yet shown
  ASSERT_TRUE(m.frame);
  EXPECT_EQ(*m.frame, 0u);
  EXPECT_TRUE(m.vr);  // since 150
  EXPECT_DOUBLE_EQ(m.ghost->position[0], 0.1);

  m = playback->at(frame0 + 0.199);  // base + 299 ms: frame 2 shown (230); the second ghost; AR
  EXPECT_EQ(*m.frame, 1u);
  EXPECT_DOUBLE_EQ(m.ghost->position[0], 0.2);
  EXPECT_EQ(m.ghost->gripper, 0.0);
  EXPECT_FALSE(m.vr);
  ASSERT_TRUE(m.frame_age_s);  // captured at base + 190 ms, seen at + 299 ms
  EXPECT_NEAR(*m.frame_age_s, 0.109, 1e-9);

  m = playback->at(frame0 + 0.210);  // base + 310 ms: frame 3 arrived (300), not yet shown
  EXPECT_EQ(*m.frame, 1u);

  m = playback->at(1e6);  // clamped to the end (frame 3 shown at 330): the last frame
  EXPECT_DOUBLE_EQ(m.t, playback->duration_s());
  EXPECT_EQ(*m.frame, 2u);

  // Both eyes decoded from the recorded JPEGs (left 200, right 40 for the last pair).
  auto frame = playback->frame(2);
  ASSERT_TRUE(frame) << frame.error().message;
  EXPECT_EQ((*frame)->left.width, 64);
  EXPECT_NEAR((*frame)->left.at(10, 10, 0), 200, 2);
  EXPECT_NEAR((*frame)->right.at(10, 10, 0), 40, 2);
  EXPECT_EQ((*frame)->index, 2u);
  auto missing = playback->frame(3);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message, "frame 3: the recording has 3");
}

TEST(RecordingPlayback, ARecordingWithoutCalibrationCannotBeDrawn) {
  test_files::TempDir tmp("playback-bare");
  auto written = write_recording(tmp.path(), false);
  ASSERT_TRUE(written) << written.error().message;
  auto playback = RecordingPlayback::open(written->path);
  ASSERT_FALSE(playback);
  EXPECT_EQ(playback.error().message,
            "'" + written->path + "' records no calibration: nothing to draw the arm through");
}

}  // namespace
}  // namespace telear::record
