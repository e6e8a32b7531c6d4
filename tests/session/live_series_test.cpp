// The live plots' series (telear/session/live_series.hpp) fed as Session::update() feeds them,
// with made-up times: the tracking error's values, the window, the video's per-second buckets,
// the capacity bound, and the binning a plot draws.

#include "telear/session/live_series.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace telear::session {
namespace {

net::RobotStateSample state(std::uint64_t sequence, Eigen::VectorXd q, Eigen::VectorXd q_cmd) {
  net::RobotStateSample s;
  s.sequence = sequence;
  s.state.q = std::move(q);
  s.state.q_commanded = std::move(q_cmd);
  return s;
}

net::DecodedStereoFrame frame(std::int64_t decoded_ns, std::size_t bytes, double total_s) {
  net::DecodedStereoFrame f;
  f.decoded_ns = decoded_ns;
  f.message_bytes = bytes;
  f.latency.network_s = 0.25 * total_s;
  f.latency.total_s = total_s;
  return f;
}

DisplayDecision shown(DisplayMode mode, bool stale = false) {
  DisplayDecision d;
  d.mode = mode;
  d.frame_stale = stale;
  return d;
}

TEST(LiveSeries, OptionsAreRefusedNamingTheField) {
  EXPECT_TRUE(LiveSeriesOptions{}.validate().ok());
  LiveSeriesOptions bad;
  bad.window_s = 0;
  EXPECT_EQ(bad.validate().error().message, "live series: window_s 0 must be positive and finite");
  bad = {};
  bad.rate_bucket_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(bad.validate().error().message,
            "live series: rate_bucket_s nan must be positive and finite");
  bad = {};
  bad.rate_bucket_s = 30;
  EXPECT_EQ(bad.validate().error().message,
            "live series: rate_bucket_s 30 must be at most window_s 20");
  bad = {};
  bad.capacity = 1;
  EXPECT_EQ(bad.validate().error().message, "live series: capacity 1 must be >= 2");
}

// One sample per new state, e = q_commanded - q per joint at the state's capture time; a
// state seen again (the client's latest-wins slot between two updates) is not counted twice.
TEST(LiveSeries, TrackingErrorIsCommandedMinusMeasuredOncePerState) {
  LiveSeries live;
  const auto s1 = state(1, Eigen::Vector3d(0.10, -0.20, 0.30), Eigen::Vector3d(0.10, -0.19, 0.28));
  live.update(1.00, &s1, 0.98, nullptr, shown(DisplayMode::kVR, true));
  live.update(1.02, &s1, 0.98, nullptr, shown(DisplayMode::kVR, true));
  ASSERT_EQ(live.tracking().size(), 1u);
  EXPECT_EQ(live.joints(), 3);
  EXPECT_DOUBLE_EQ(live.tracking()[0].t, 0.98);
  EXPECT_NEAR(live.tracking()[0].error[0], 0.0, 1e-15);
  EXPECT_NEAR(live.tracking()[0].error[1], 0.01, 1e-15);
  EXPECT_NEAR(live.tracking()[0].error[2], -0.02, 1e-15);

  // Not a sample: another joint count, a NaN, no servo command; the next good one is.
  const auto wrong_size = state(2, Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0));
  live.update(1.04, &wrong_size, 1.03, nullptr, shown(DisplayMode::kVR));
  const auto nan = state(3, Eigen::Vector3d(std::nan(""), 0, 0), Eigen::Vector3d(0, 0, 0));
  live.update(1.06, &nan, 1.05, nullptr, shown(DisplayMode::kVR));
  const auto no_command = state(4, Eigen::Vector3d(0, 0, 0), Eigen::VectorXd());
  live.update(1.08, &no_command, 1.07, nullptr, shown(DisplayMode::kVR));
  const auto s5 = state(5, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3.5));
  live.update(1.10, &s5, 1.09, nullptr, shown(DisplayMode::kVR));
  ASSERT_EQ(live.tracking().size(), 2u);
  EXPECT_DOUBLE_EQ(live.tracking().back().t, 1.09);
  EXPECT_DOUBLE_EQ(live.tracking().back().error[2], 0.5);
  EXPECT_EQ(live.display().size(), 6u);  // one per update, whatever the states did
}

// 30 frames a second of 1000 bytes for 3 s, then 2 s of no video at 60 updates a second: the
// buckets read 30 fps and 30 kB/s, then 0, and each frame's latency is one sample.
TEST(LiveSeries, VideoFpsAndBandwidthPerSecondBucket) {
  LiveSeries live;
  std::int64_t decoded_ns = 1'000'000'000;
  for (int k = 0; k < 90; ++k) {
    const double t = 0.005 + k / 30.0;
    decoded_ns += 33'000'000;
    const auto f = frame(decoded_ns, 1000, 0.010 + 0.001 * (k % 3));
    live.update(t, nullptr, 0.0, &f, shown(DisplayMode::kAR));
    live.update(t + 0.01, nullptr, 0.0, &f, shown(DisplayMode::kAR));  // the same frame again
  }
  for (int k = 0; k < 120; ++k) {
    live.update(3.0 + k / 60.0, nullptr, 0.0, nullptr, shown(DisplayMode::kVR, true));
  }
  const auto& video = live.video();
  ASSERT_EQ(video.size(), 5u);  // [0, 1) .. [4, 5), the last still filling
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(video[i].t, static_cast<double>(i));
    EXPECT_EQ(video[i].frames, 30) << i;
    EXPECT_DOUBLE_EQ(video[i].fps(), 30.0);
    EXPECT_DOUBLE_EQ(video[i].bytes_per_s(), 30000.0);
  }
  EXPECT_EQ(video[3].frames, 0);
  EXPECT_EQ(video[4].frames, 0);

  ASSERT_EQ(live.latency().size(), 90u);
  EXPECT_DOUBLE_EQ(live.latency()[4].latency.total_s, 0.011);
  EXPECT_DOUBLE_EQ(live.latency()[4].latency.network_s, 0.25 * 0.011);
  EXPECT_DOUBLE_EQ(live.latency()[4].t, 0.005 + 4 / 30.0);
  EXPECT_EQ(live.display().back().mode, DisplayMode::kVR);
  EXPECT_TRUE(live.display().back().stale);
  EXPECT_EQ(live.display().front().mode, DisplayMode::kAR);
}

// Everything older than window_s before the newest update goes, the buckets included; a gap
// longer than the window leaves one bucket.
TEST(LiveSeries, KeepsTheLastWindowOnly) {
  LiveSeriesOptions options;
  options.window_s = 5.0;
  LiveSeries live(options);
  std::int64_t decoded_ns = 0;
  for (int k = 1; k <= 300; ++k) {  // 30 s at 10 Hz
    const double t = k * 0.1;
    const auto s = state(k, Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0));
    const auto f = frame(decoded_ns += 100'000'000, 10, 0.01);
    live.update(t, &s, t - 0.02, &f, shown(DisplayMode::kAR));
  }
  ASSERT_FALSE(live.tracking().empty());
  ASSERT_FALSE(live.latency().empty());
  EXPECT_GE(live.tracking().front().t, 30.0 - 5.0);
  EXPECT_LT(live.tracking().front().t, 30.0 - 5.0 + 0.1 + 1e-9);
  EXPECT_GE(live.latency().front().t, 25.0);
  EXPECT_GE(live.display().front().t, 25.0);
  EXPECT_EQ(live.display().size(), 51u);          // 25.0 .. 30.0
  EXPECT_GT(live.video().front().t + 1.0, 25.0);  // the oldest bucket ends inside the window
  EXPECT_EQ(live.video().size(), 6u);             // [25, 26) .. [30, 31)

  live.update(100.0, nullptr, 0.0, nullptr, shown(DisplayMode::kVR, true));
  EXPECT_TRUE(live.tracking().empty());
  EXPECT_TRUE(live.latency().empty());
  EXPECT_EQ(live.display().size(), 1u);
  ASSERT_EQ(live.video().size(), 1u);
  EXPECT_DOUBLE_EQ(live.video().front().t, 100.0);
  EXPECT_EQ(live.video().front().frames, 0);
}

// A console drawing faster than capacity / window_s keeps fewer samples, never more: each
// series holds at most `capacity`, the newest.
TEST(LiveSeries, CapacityBoundsEverySeries) {
  LiveSeriesOptions options;
  options.capacity = 8;
  LiveSeries live(options);
  for (int k = 1; k <= 100; ++k) {
    const double t = k * 0.001;
    const auto s = state(k, Eigen::Vector2d(k, 0), Eigen::Vector2d(0, 0));
    const auto f = frame(k, 10, 0.01);
    live.update(t, &s, t, &f, shown(DisplayMode::kAR));
  }
  EXPECT_EQ(live.tracking().size(), 8u);
  EXPECT_EQ(live.tracking().capacity(), 8u);
  EXPECT_DOUBLE_EQ(live.tracking().front().error[0], -93.0);
  EXPECT_DOUBLE_EQ(live.tracking().back().error[0], -100.0);
  EXPECT_EQ(live.latency().size(), 8u);
  EXPECT_EQ(live.display().size(), 8u);
  EXPECT_DOUBLE_EQ(live.display().front().t, 0.093);
  EXPECT_LE(live.video().capacity(), 8u);
  EXPECT_EQ(live.video().back().frames, 100);  // all in the first second's bucket
}

// The plot's bins: the value of largest magnitude in each (a spike survives), an empty bin
// repeats the one before (0 before the first sample), samples outside the span left out.
TEST(LiveSeries, BinsKeepTheLargestMagnitudeAndRepeatOverGaps) {
  core::RingBuffer<TrackingSample> samples(16);
  auto add = [&](double t, double e) { samples.push({t, Eigen::VectorXd::Constant(1, e)}); };
  add(-0.5, 9.0);  // before the span
  add(0.25, 0.1);
  add(1.10, 0.2);
  add(1.20, -0.7);
  add(1.30, 0.3);
  add(3.90, 0.4);
  add(4.00, 0.5);  // the span's end: the last bin
  add(4.50, 9.0);  // after it
  const auto error = [](const TrackingSample& s) { return s.error[0]; };
  const std::vector<float> bins = bin_by_time(samples, 4.0, 4.0, 4, error);
  ASSERT_EQ(bins.size(), 4u);
  EXPECT_FLOAT_EQ(bins[0], 0.1f);
  EXPECT_FLOAT_EQ(bins[1], -0.7f);
  EXPECT_FLOAT_EQ(bins[2], -0.7f);  // empty: repeats
  EXPECT_FLOAT_EQ(bins[3], 0.5f);

  core::RingBuffer<TrackingSample> late(4);
  late.push({3.5, Eigen::VectorXd::Constant(1, 2.0)});
  const std::vector<float> leading = bin_by_time(late, 4.0, 4.0, 4, error);
  EXPECT_EQ(leading, (std::vector<float>{0.0f, 0.0f, 0.0f, 2.0f}));
}

}  // namespace
}  // namespace telear::session
