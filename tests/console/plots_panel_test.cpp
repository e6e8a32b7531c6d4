// The console's Plots panel (plots_panel.cpp) headless against the embedded simulated servers:
// `view plots on` from a UI script shows it, the session's live series have filled from the real
// streams (states, frames, display frames), and the panel's plots are drawn over the plan and
// status panels (their colours counted in that region of the console's image, against the same
// console with the panel off).

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>

#include "apps/console_command.hpp"
#include "scripted_console.hpp"
#include "telear/console/console_actions.hpp"
#include "telear/console/console_app.hpp"
#include "telear/console/panels.hpp"
#include "telear/core/clock.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::console {
namespace {

constexpr int kPlotsConsoleWidth = 1280, kPlotsConsoleHeight = 800;

// Pixels of a kind in the Plots panel's first-use region (over the plan and status panels:
// PanelLayout, below the view, left of the right-hand column).
template <typename Kind>
int count_pixels(const core::Image& image, Kind kind) {
  const PanelLayout layout{static_cast<float>(image.width), static_cast<float>(image.height)};
  int n = 0;
  for (int y = static_cast<int>(layout.view_h()) + 30;
       y < image.height - static_cast<int>(layout.bar_h()); ++y) {
    for (int x = 0; x < static_cast<int>(layout.view_w()); ++x) {
      if (kind(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2))) ++n;
    }
  }
  return n;
}

// The panel's colours (plots_panel.cpp): the tracking error's light blue lines (115, 199, 255),
// blended half and half with the plot's dark blue frame by the antialiasing of a line between two
// pixel rows, and the video rate's green bars.
int tracking_pixels(const core::Image& image) {
  return count_pixels(image, [](int r, int g, int b) {
    return r >= 55 && r <= 130 && g >= 100 && b >= 140 && b >= r + 60;
  });
}
int rate_pixels(const core::Image& image) {
  return count_pixels(image,
                      [](int r, int g, int b) { return g > 150 && g > r + 60 && g > b + 50; });
}

TEST(PlotsPanel, ShowsTheSessionsLiveSeries) {
  test_files::TempDir tmp("console_plots");
  const std::string script = (tmp.path() / "plots.txt").string();
  // 1 s of video with the panel open: the second (bucket) the video began in is complete.
  std::ofstream(script) << "wait-until video 30\n"
                           "view plots on\n"
                           "wait 1\n";
  const ConsoleOptions options =
      telear::test::scripted_headless_console(script, kPlotsConsoleWidth, kPlotsConsoleHeight);
  std::ostringstream log;
  auto created = ConsoleApp::create(options, log);
  ASSERT_TRUE(created) << created.error().message;
  ConsoleApp& app = **created;
  const auto start = std::chrono::steady_clock::now();
  while (!app.script().finished()) {
    ASSERT_TRUE(app.frame()) << log.str();
    ASSERT_LT(core::seconds_since(start), 40.0) << log.str();
  }
  ASSERT_EQ(app.script().failures(), 0) << log.str();
  EXPECT_TRUE(app.ui().show_plots);

  // The series the panel draws, fed by Session::update() from the real streams.
  const session::LiveSeries& live = app.session().live_series();
  EXPECT_EQ(live.joints(), 6);
  EXPECT_GT(live.tracking().size(), 10u);
  EXPECT_GT(live.latency().size(), 5u);
  EXPECT_GT(live.latency().back().latency.total_s, 0.0);
  ASSERT_GE(live.video().size(), 2u);
  int frames = 0;
  for (std::size_t i = 0; i + 1 < live.video().size(); ++i) frames += live.video()[i].frames;
  EXPECT_GT(frames, 0);  // in the complete buckets
  EXPECT_GT(live.display().size(), 10u);

  app.set_capture_every_frame(true);
  ASSERT_TRUE(app.frame());
  const core::Image shown = app.last_image();
  ASSERT_TRUE(apply_action(app.session(), app.ui(), {.kind = ActionKind::kViewPlots}).ok());
  ASSERT_TRUE(app.frame());
  const core::Image hidden = app.last_image();
  // Six joints' lines, at 0 in the middle of each; a second's fps and MB/s bars at least.
  EXPECT_GT(tracking_pixels(shown), tracking_pixels(hidden) + 6 * 150);
  EXPECT_GT(rate_pixels(shown), rate_pixels(hidden) + 100);
  app.session().disconnect();
}

}  // namespace
}  // namespace telear::console
