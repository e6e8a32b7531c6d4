// Glass to glass in the session (Session::note_shown, SessionStats::shown): each drawn frame
// counts once, its frame code's capture time against the read-back's time; a frame without
// its own code counts as not measured; the figure covers the last ~2 s only.

#include <gtest/gtest.h>

#include "telear/core/clock.hpp"
#include "telear/session/session.hpp"
#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

std::unique_ptr<Session> unconnected_session() {
  SessionOptions options;
  options.robot.address = "127.0.0.1:1";  // never connected: no clock offset, the identity
  options.vision.address = "127.0.0.1:1";
  auto session = Session::create(telear::test::puma560(), options);
  EXPECT_TRUE(session) << session.error().message;
  return std::move(*session);
}

TEST(SessionShown, EachFrameCountsOnceWithItsCodesCaptureTime) {
  auto session = unconnected_session();
  EXPECT_EQ(session->stats().shown.samples, 0);
  const std::int64_t now = core::monotonic_ns();
  EXPECT_FALSE(session->shown_noted(7));
  session->note_shown(7, vision::FrameCode{7, now - 12'000'000}, now);
  EXPECT_TRUE(session->shown_noted(7));
  // The same frame drawn again (the console draws faster than the video) is not counted.
  session->note_shown(7, vision::FrameCode{7, now - 12'000'000}, now + 16'000'000);
  session->note_shown(8, vision::FrameCode{8, now - 20'000'000}, now);
  const SessionStats stats = session->stats();
  EXPECT_EQ(stats.shown.samples, 2);
  EXPECT_NEAR(stats.shown.p50_s, 0.012, 1e-9);  // nearest rank: the lower of two
  EXPECT_NEAR(stats.shown.p99_s, 0.020, 1e-9);
  EXPECT_EQ(stats.shown_without_code, 0);
}

TEST(SessionShown, AFrameWithoutItsOwnCodeIsNotMeasured) {
  auto session = unconnected_session();
  const std::int64_t now = core::monotonic_ns();
  session->note_shown(3, std::nullopt, now);                            // no code read
  session->note_shown(4, vision::FrameCode{99, now - 5'000'000}, now);  // another frame's
  const SessionStats stats = session->stats();
  EXPECT_EQ(stats.shown.samples, 0);
  EXPECT_EQ(stats.shown_without_code, 2);
  EXPECT_TRUE(session->shown_noted(4));
}

}  // namespace
}  // namespace telear::session
