#include "telear/report/recording_summary.hpp"

#include <filesystem>

#include "telear/core/number_format.hpp"

namespace telear::report {
namespace {

std::string fixed(double v, int digits) {
  return core::format_fixed(v, digits);
}

// Text inside a Markdown table cell: a '|' would end the cell, a newline the row.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

std::string metadata_value(const record::RecordingSeries& series, const std::string& record,
                           const std::string& key) {
  const auto r = series.metadata.find(record);
  if (r == series.metadata.end()) return "";
  const auto v = r->second.find(key);
  return v == r->second.end() ? "" : v->second;
}

const char* level_name(record::LogLevel level) {
  switch (level) {
    case record::LogLevel::kDebug:
      return "debug";
    case record::LogLevel::kWarning:
      return "warning";
    case record::LogLevel::kError:
      return "error";
    default:
      return "info";
  }
}

// The plot named `name` embedded under its title, if it was drawn.
std::string embed(const std::vector<PlotFile>& plots, std::string_view name) {
  for (const PlotFile& p : plots) {
    if (p.name == name) return "\n![" + p.title + "](" + p.name + ")\n";
  }
  return "";
}

}  // namespace

std::string recording_summary_markdown(const record::RecordingSeries& series,
                                       const RecordingStatistics& s,
                                       const std::vector<PlotFile>& plots,
                                       const std::string& plot_note) {
  const std::string file = std::filesystem::path(series.path).filename().string();
  std::string md = "# Recording " + file + "\n\n";
  md += "| | |\n|---|---|\n";
  md += "| file | `" + cell(series.path) + "` |\n";
  md += "| duration | " + fixed(s.duration_s, 2) + " s |\n";
  if (const std::string robot = metadata_value(series, "telear.session", "robot"); !robot.empty())
    md += "| robot | " + cell(robot) + " |\n";
  if (const std::string by = metadata_value(series, "telear.session", "recorded_by"); !by.empty())
    md += "| recorded by | " + cell(by) + " |\n";
  if (const std::string v = metadata_value(series, "telear.session", "telear_version"); !v.empty())
    md += "| telear | " + cell(v) + " |\n";
  md += std::string("| closed | ") +
        (series.complete ? "yes"
                         : "no: the recorder did not close it (killed?); read up to its last "
                           "complete chunk") +
        " |\n";
  md += "| items dropped by the recorder | " +
        (s.dropped_total ? std::to_string(*s.dropped_total)
                         : std::string("unknown (no telear.recording metadata)")) +
        " |\n\n";

  md += "## Messages per topic\n\n| topic | messages | dropped |\n|---|---|---|\n";
  for (const auto& [topic, n] : series.message_counts) {
    const auto dropped = s.dropped.find(topic);
    md += "| `" + topic + "` | " + std::to_string(n) + " | " +
          (dropped == s.dropped.end() ? std::string(s.dropped_total ? "0" : "?")
                                      : std::to_string(dropped->second)) +
          " |\n";
  }

  md += "\n## Joint tracking error\n\nCommanded - measured at each recorded state (" +
        std::to_string(s.tracking_samples) +
        " states with their command; `/robot/joint_commands` against `/robot/joint_states`).\n\n";
  if (s.tracking.empty()) {
    md += "No joint commands recorded.\n";
  } else {
    md += "| joint | unit | RMS | max abs |\n|---|---|---|---|\n";
    for (const JointTrackingError& j : s.tracking) {
      // Three significant digits: a simulated arm's errors are 1e-6 deg, a real one's 0.1.
      md += "| " + cell(j.joint) + " | " + j.unit.name + " | " +
            core::format_number(j.rms, "%.3g") + " | " + core::format_number(j.max_abs, "%.3g") +
            " |\n";
    }
  }
  md += embed(plots, kTrackingErrorPlot);

  md += "\n## Video latency per stage\n\n";
  if (s.latency.total_s.empty()) {
    md += "No latency recorded (`/telear/latency`).\n";
  } else {
    md +=
        "Per decoded stereo frame, `/telear/latency` (nearest-rank percentiles).\n\n"
        "| stage | median ms | p95 ms | frames |\n|---|---|---|---|\n";
    for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) {
      const StageFigures& f = s.latency.stages[i];
      md += std::string("| ") + net::kLatencyStages[i].long_label + " | " +
            fixed(f.median_s * 1e3, 2) + " | " + fixed(f.p95_s * 1e3, 2) + " | " +
            std::to_string(f.samples) + " |\n";
    }
  }
  md += embed(plots, kLatencyStagesPlot);
  md += embed(plots, kLatencyTotalPlot);

  md +=
      "\n## Video\n\nJPEG frames as received, per camera (MB = 10^6 bytes).\n\n"
      "| camera | frames | fps mean | MB/s mean | MB |\n|---|---|---|---|---|\n";
  for (const CameraRate& c : s.cameras) {
    md += "| " + c.camera + " | " + std::to_string(c.frames) + " | " + fixed(c.fps_mean, 2) +
          " | " + fixed(c.mb_per_s_mean, 3) + " | " + fixed(static_cast<double>(c.bytes) / 1e6, 2) +
          " |\n";
  }
  md += embed(plots, kVideoRatePlot);

  md += "\n## Display mode (AR / VR)\n\n";
  if (s.display.empty()) {
    md += "No AR/VR switches recorded.\n";
  } else {
    int to_vr = 0, to_ar = 0;
    for (const DisplaySwitch& d : s.display) (d.mode == DisplayMode::kVr ? to_vr : to_ar)++;
    md += "Switches to VR: " + std::to_string(to_vr) + ", to AR: " + std::to_string(to_ar) +
          " (AR: the live video behind the ghost; VR: the scene drawn from the robot's reported "
          "state, the video being late or stopped).\n\n";
    for (const DisplaySwitch& d : s.display) {
      md += "- t = " + fixed(d.t, 2) + " s: " + (d.mode == DisplayMode::kVr ? "VR" : "AR") + " (" +
            d.text + ")\n";
    }
  }
  md += embed(plots, kDisplayModePlot);

  md += "\n## Events\n\n";
  if (series.events.empty()) {
    md += "No events recorded (`/events`).\n";
  } else {
    md += "| t (s) | level | event |\n|---|---|---|\n";
    for (std::size_t i = 0; i < series.events.size() && i < kMaxSummaryEvents; ++i) {
      const record::EventSample& e = series.events[i];
      md += "| " + fixed(e.t, 2) + " | " + level_name(e.level) + " | " + cell(e.text) + " |\n";
    }
    if (series.events.size() > kMaxSummaryEvents) {
      md += "\n... and " + std::to_string(series.events.size() - kMaxSummaryEvents) +
            " more (`/events` in the file).\n";
    }
  }
  if (!plot_note.empty()) md += "\n" + plot_note + "\n";
  return md;
}

}  // namespace telear::report
