// The Plots panel: the session's live series (telear/session/live_series.hpp) over their
// window, newest at the right, with Dear ImGui's own plot widgets (Debian has no ImPlot). The
// panel computes what it draws each frame from the series and keeps nothing.

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "telear/console/panels.hpp"

namespace telear::console {

namespace {

// Time bins of the line plots: 0.1 s each over the default 20 s window, about two pixels each
// on a plot a third of the panel wide (a bin holds a few states or frames at their rates).
constexpr int kPlotTimeBins = 200;

const ImVec4 kTrackingLine(0.45f, 0.78f, 1.0f, 1);
const ImVec4 kLatencyLine(0.85f, 0.85f, 0.85f, 1);
const ImVec4 kTotalLatencyLine(1.0f, 0.85f, 0.35f, 1);
const ImVec4 kRateBars(0.35f, 0.75f, 0.4f, 1);
const ImVec4 kVrBars(0.95f, 0.7f, 0.2f, 1);  // the console's VR amber
// A line plot's scale reaches this far above its largest value, so that the newest value and
// the peaks stay under the overlay text at the plot's top.
constexpr double kOverlayHeadroom = 1.6;

// The height each of `n` plots gets from what is left in the column.
float plot_height(float available, int n) {
  const float spacing = ImGui::GetStyle().ItemSpacing.y;
  return std::max(22.0f, (available - static_cast<float>(n) * spacing) / static_cast<float>(n));
}

// The column's width: PlotLines / PlotHistogram take no negative ("to the right edge") size.
ImVec2 plot_size(float height) {
  return ImVec2(std::max(40.0f, ImGui::GetContentRegionAvail().x), height);
}

void plot_lines(const char* id, const std::vector<float>& values, const char* overlay, float lo,
                float hi, float height, const ImVec4& colour) {
  ImGui::PushStyleColor(ImGuiCol_PlotLines, colour);
  ImGui::PlotLines(id, values.data(), static_cast<int>(values.size()), 0, overlay, lo, hi,
                   plot_size(height));
  ImGui::PopStyleColor();
}

// Bars fill their plot to the top: the caption goes above it, not over it.
void plot_bars(const char* id, const std::vector<float>& values, const char* caption, float hi,
               float height, const ImVec4& colour) {
  ImGui::TextUnformatted(caption);
  ImGui::PushStyleColor(ImGuiCol_PlotHistogram, colour);
  ImGui::PlotHistogram(id, values.data(), static_cast<int>(values.size()), 0, nullptr, 0.0f, hi,
                       plot_size(height));
  ImGui::PopStyleColor();
}

// [SECTION] tracking error per joint
void draw_tracking_column(const session::Session& s, float available) {
  const session::LiveSeries& live = s.live_series();
  const auto& samples = live.tracking();
  if (live.joints() == 0) {
    ImGui::TextDisabled("no robot state yet");
    return;
  }
  // The model's joints (a robot reporting more is refused elsewhere: the ghost needs them).
  const core::RobotModel& model = s.model();
  const int joints = std::min(live.joints(), model.dof());
  const float h = plot_height(available, joints);
  for (int j = 0; j < joints; ++j) {
    // In the console's joint units (degrees, mm for a prismatic joint), as the report plots it.
    auto error = [&model, j](const session::TrackingSample& sample) {
      return display_value(model, j, sample.error[j]);
    };
    double worst = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      worst = std::max(worst, std::abs(error(samples[i])));
    }
    const double now = samples.empty() ? 0.0 : error(samples.back());
    char overlay[128];
    std::snprintf(overlay, sizeof overlay, "%s %+.4f %s, max |e| %.4f", model.joint(j).name.c_str(),
                  now, is_prismatic(model, j) ? "mm" : "deg", worst);
    // Symmetric about 0, so that 0 is the middle line; a floor keeps a zero error flat.
    const auto limit = static_cast<float>(std::max(worst * kOverlayHeadroom, 1e-4));
    char id[32];
    std::snprintf(id, sizeof id, "##track%d", j);
    plot_lines(
        id,
        session::bin_by_time(samples, live.now(), live.options().window_s, kPlotTimeBins, error),
        overlay, -limit, limit, h, kTrackingLine);
  }
}

// [SECTION] latency per stage
void draw_latency_column(const session::LiveSeries& live, float available) {
  const auto& samples = live.latency();
  if (samples.empty()) {
    ImGui::TextDisabled("no video frame yet");
    return;
  }
  const float h = plot_height(available, static_cast<int>(net::kLatencyStageCount));
  for (std::size_t k = 0; k < net::kLatencyStageCount; ++k) {
    const net::LatencyStage& stage = net::kLatencyStages[k];
    auto ms = [&stage](const session::FrameLatencySample& sample) {
      return stage.of(sample.latency) * 1e3;
    };
    double worst = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) worst = std::max(worst, ms(samples[i]));
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, "%s %.1f ms, max %.1f", stage.label, ms(samples.back()),
                  worst);
    char id[32];
    std::snprintf(id, sizeof id, "##latency%zu", k);
    plot_lines(
        id, session::bin_by_time(samples, live.now(), live.options().window_s, kPlotTimeBins, ms),
        overlay, 0.0f, static_cast<float>(std::max(worst * kOverlayHeadroom, 0.01)), h,
        k == net::kTotalLatencyStage ? kTotalLatencyLine : kLatencyLine);
  }
}

// [SECTION] video rate and AR / VR
void draw_video_column(const session::LiveSeries& live, float available) {
  const float h = plot_height(available - 3 * ImGui::GetTextLineHeightWithSpacing(), 3);
  // One bar per complete bucket, right-aligned on the window's buckets (the newest bucket is
  // still filling and would read low).
  const auto& buckets = live.video();
  const auto bars =
      static_cast<std::size_t>(std::lround(live.options().window_s / live.options().rate_bucket_s));
  std::vector<float> fps(bars, 0.0f), mbps(bars, 0.0f);
  const std::size_t complete = buckets.empty() ? 0 : buckets.size() - 1;
  const std::size_t shown = std::min(bars, complete);
  for (std::size_t i = 0; i < shown; ++i) {
    const session::VideoRateBucket& b = buckets[complete - shown + i];
    fps[bars - shown + i] = static_cast<float>(b.fps());
    mbps[bars - shown + i] = static_cast<float>(b.bytes_per_s() / 1e6);
  }
  const float last_fps = fps.empty() ? 0.0f : fps.back();
  const float last_mbps = mbps.empty() ? 0.0f : mbps.back();
  char caption[96];
  std::snprintf(caption, sizeof caption, "video fps: %.1f (per %g s)", last_fps,
                live.options().rate_bucket_s);
  const float max_fps = fps.empty() ? 0.0f : *std::max_element(fps.begin(), fps.end());
  plot_bars("##fps", fps, caption, std::max(1.0f, max_fps * 1.15f), h, kRateBars);
  std::snprintf(caption, sizeof caption, "video bandwidth: %.2f MB/s", last_mbps);
  const float max_mbps = mbps.empty() ? 0.0f : *std::max_element(mbps.begin(), mbps.end());
  plot_bars("##mbps", mbps, caption, std::max(0.01f, max_mbps * 1.15f), h, kRateBars);

  // VR a full bar, AR over a stale frame (forced AR) half of one, live AR none.
  const auto& display = live.display();
  auto level = [](const session::DisplaySample& d) {
    return d.mode == session::DisplayMode::kVR ? 1.0 : d.stale ? 0.5 : 0.0;
  };
  double vr_s = 0.0;
  int to_vr = 0;
  for (std::size_t i = 1; i < display.size(); ++i) {
    if (display[i - 1].mode == session::DisplayMode::kVR) vr_s += display[i].t - display[i - 1].t;
    if (display[i].mode == session::DisplayMode::kVR &&
        display[i - 1].mode == session::DisplayMode::kAR) {
      ++to_vr;
    }
  }
  const bool vr_now = !display.empty() && display.back().mode == session::DisplayMode::kVR;
  std::snprintf(caption, sizeof caption, "AR / VR: now %s; VR %.1f s, %d AR->VR switches",
                vr_now ? "VR" : "AR", vr_s, to_vr);
  plot_bars(
      "##arvr",
      session::bin_by_time(display, live.now(), live.options().window_s, kPlotTimeBins, level),
      caption, 1.0f, h, kVrBars);
}

}  // namespace

void draw_plots_panel(PanelContext& ctx, const PanelLayout& layout) {
  if (!ctx.ui.show_plots) return;
  const session::Session& s = ctx.session;
  ImGui::SetNextWindowPos(ImVec2(0, layout.view_h()), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(
      ImVec2(layout.view_w(), layout.height - layout.bar_h() - layout.view_h()),
      ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(1.0f);  // it lies over the plan and status panels
  char title[64];
  std::snprintf(title, sizeof title, "Plots: the last %.0f s, newest at the right###Plots",
                s.live_series().options().window_s);
  if (!ImGui::Begin(title, &ctx.ui.show_plots)) {
    ImGui::End();
    return;
  }
  if (ImGui::BeginTable("plots", 3,
                        ImGuiTableFlags_SizingStretchSame | ImGuiTableFlags_BordersInnerV)) {
    ImGui::TableSetupColumn("tracking error: commanded - measured");
    ImGui::TableSetupColumn("latency per frame, by stage");
    ImGui::TableSetupColumn("video rate and AR / VR");
    ImGui::TableHeadersRow();
    ImGui::TableNextRow();
    // What is left under the headers, less the cell's padding and the last item's spacing (no
    // scroll bar).
    const ImGuiStyle& style = ImGui::GetStyle();
    const float available =
        ImGui::GetContentRegionAvail().y - 2 * style.CellPadding.y - style.ItemSpacing.y;
    ImGui::TableNextColumn();
    draw_tracking_column(s, available);
    ImGui::TableNextColumn();
    draw_latency_column(s.live_series(), available);
    ImGui::TableNextColumn();
    draw_video_column(s.live_series(), available);
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace telear::console
