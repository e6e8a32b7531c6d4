#include "telear/report/recording_plots.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>
#include <utility>

#include "gnuplot_process.hpp"
#include "telear/core/number_format.hpp"

namespace telear::report {
namespace {

using Points = std::vector<std::pair<double, double>>;

// Colours: the cameras as the console's status panel draws them, the display modes as the AR
// view's frame (green AR, amber VR), the stages from a qualitative palette.
constexpr const char* kLeftColour = "#1f77b4";
constexpr const char* kRightColour = "#d62728";
constexpr const char* kArColour = "#2ca02c";
constexpr const char* kVrColour = "#ff9f1a";
constexpr std::array<const char*, 5> kStageColours = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2",
                                                      "#59a14f"};

// A gnuplot string literal: single quotes take everything literally but a quote, doubled.
std::string quoted(std::string_view text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

std::string number(double v, int digits) {
  return core::format_fixed(v, digits);
}

// Starts a plot: settings back to their defaults, the PNG's size and file. (`reset` keeps the
// terminal and the output, so both are set each time.)
void begin(gnuplotio::Gnuplot& gp, const PlotFile& plot) {
  gp << "reset\n"
     << "set terminal pngcairo noenhanced size " << plot.width_px << "," << plot.height_px
     << " font 'Sans,10'\n"
     << "set output " << quoted(plot.path) << "\n";
}

// Closes the PNG (gnuplot writes it when its output changes).
void end(gnuplotio::Gnuplot& gp) {
  gp << "set output\n";
}

// An empty plot that says what is missing, with the axes still drawn.
void plot_nothing(gnuplotio::Gnuplot& gp, std::string_view why) {
  gp << "set label 99 " << quoted(why) << " at graph 0.5, graph 0.5 center font ',12'\n"
     << "unset ytics\nset yrange [0:1]\nplot NaN notitle\nunset label 99\n";
}

// The time axis every plot against time shares: the whole recording.
void time_axis(gnuplotio::Gnuplot& gp, double duration_s, bool label) {
  gp << "set xrange [0:" << std::max(duration_s, 1e-3) << "]\n";
  gp << (label ? "set xlabel 'time since the recording started (s)'\n" : "unset xlabel\n");
}

void tracking_plot(gnuplotio::Gnuplot& gp, const RecordingStatistics& s, const PlotFile& plot) {
  begin(gp, plot);
  const std::size_t panels = std::max<std::size_t>(1, s.tracking.size());
  gp << "set multiplot layout " << panels << ",1 title "
     << quoted("Joint tracking error: commanded - measured (" + std::to_string(s.tracking_samples) +
               " states)")
     << " font ',12'\n"
     << "set grid\nset key top right opaque box\n";
  if (s.tracking.empty()) {
    time_axis(gp, s.duration_s, true);
    plot_nothing(gp, "no joint commands recorded (/robot/joint_commands)");
  }
  for (std::size_t i = 0; i < s.tracking.size(); ++i) {
    const JointTrackingError& j = s.tracking[i];
    time_axis(gp, s.duration_s, i + 1 == s.tracking.size());
    gp << "set ylabel " << quoted(j.joint + " (" + j.unit.name + ")") << "\n";
    if (j.error.empty()) {
      plot_nothing(gp, "no samples of " + j.joint);
      gp << "set ytics\nset yrange [*:*]\n";
      continue;
    }
    Points points(j.t.size());
    for (std::size_t k = 0; k < j.t.size(); ++k) points[k] = {j.t[k], j.error[k]};
    // The range holds zero (no error) and the data, with room at the top for the key: gnuplot's
    // own autoscale would blow a constant error's rounding noise up to the panel's height.
    double lo = 0.0, hi = 0.0;
    for (double e : j.error) {
      lo = std::min(lo, e);
      hi = std::max(hi, e);
    }
    if (hi - lo < 1e-9) {
      lo -= 1.0;
      hi += 1.0;
    }
    const double span = hi - lo;
    gp << "set yrange [" << lo - 0.05 * span << ":" << hi + 0.35 * span << "]\n";
    gp << "plot '-' with lines lw 1.5 lc rgb '" << kLeftColour << "' title "
       << quoted("RMS " + core::format_number(j.rms, "%.3g") + " " + j.unit.name + ", max |e| " +
                 core::format_number(j.max_abs, "%.3g") + " " + j.unit.name)
       << "\n";
    gp.send1d(points);
  }
  gp << "unset multiplot\n";
  end(gp);
}

std::string window_label(const LatencyWindow& w, double duration_s) {
  const int digits = duration_s < 10.0 ? 1 : 0;
  return number(w.start_s, digits) + "-" + number(w.end_s, digits) + " s";
}

void latency_stages_plot(gnuplotio::Gnuplot& gp, const RecordingStatistics& s,
                         const PlotFile& plot) {
  begin(gp, plot);
  const LatencyFigures& l = s.latency;
  gp << "set title " << quoted("Video latency per stage: median of each stage, stacked") << "\n"
     << "set ylabel 'median latency (ms)'\nset xlabel 'frames decoded in'\n";
  if (l.total_s.empty()) {
    plot_nothing(gp, "no latency recorded (/telear/latency)");
    end(gp);
    return;
  }
  // One row per bar: its label, then the five stages' medians in ms (the total is their sum's
  // counterpart, not a stage of its own).
  using Row = std::tuple<std::string, double, double, double, double, double>;
  std::vector<Row> rows;
  const auto row = [](const std::string& label, const auto& median_s) {
    return Row{"\"" + label + "\"", median_s(0) * 1e3, median_s(1) * 1e3,
               median_s(2) * 1e3,   median_s(3) * 1e3, median_s(4) * 1e3};
  };
  rows.push_back(row("whole recording (" + std::to_string(l.total_s.size()) + " frames)",
                     [&l](std::size_t i) { return l.stages[i].median_s; }));
  for (const LatencyWindow& w : l.windows) {
    rows.push_back(
        row(window_label(w, s.duration_s), [&w](std::size_t i) { return w.median_s[i]; }));
  }
  gp << "set style data histograms\nset style histogram rowstacked\n"
     << "set style fill solid 1.0 border -1\nset boxwidth 0.6 relative\n"
     << "set yrange [0:*]\nset grid ytics\nset key outside right top vertical\n"
     << "set xtics nomirror rotate by -20\n";
  gp << "plot ";
  for (std::size_t i = 0; i + 1 < net::kLatencyStageCount; ++i) {
    gp << (i > 0 ? ", " : "") << "'-' using " << i + 2 << (i == 0 ? ":xtic(1)" : "") << " title "
       << quoted(net::kLatencyStages[i].long_label) << " lc rgb '" << kStageColours[i] << "'";
  }
  gp << "\n";
  for (std::size_t i = 0; i + 1 < net::kLatencyStageCount; ++i) gp.send1d(rows);
  end(gp);
}

void latency_total_plot(gnuplotio::Gnuplot& gp, const RecordingStatistics& s,
                        const PlotFile& plot) {
  begin(gp, plot);
  const LatencyFigures& l = s.latency;
  gp << "set title " << quoted("Video latency capture -> decoded: distribution") << "\n"
     << "set xlabel 'capture -> decoded latency (ms)'\nset ylabel 'frames'\n";
  if (l.total_s.empty()) {
    plot_nothing(gp, "no latency recorded (/telear/latency)");
    end(gp);
    return;
  }
  // Bins of equal width over the measured range, about sqrt(n) of them (5..40).
  std::vector<double> ms;
  for (double t : l.total_s) ms.push_back(t * 1e3);
  double lo = *std::min_element(ms.begin(), ms.end());
  double hi = *std::max_element(ms.begin(), ms.end());
  if (hi - lo < 1e-6) {
    lo -= 0.5;
    hi += 0.5;
  }
  const int bins =
      std::clamp(static_cast<int>(std::lround(std::sqrt(static_cast<double>(ms.size())))), 5, 40);
  const double width = (hi - lo) / bins;
  std::vector<int> counts(static_cast<std::size_t>(bins), 0);
  for (double v : ms) {
    const int b = std::min(bins - 1, static_cast<int>((v - lo) / width));
    ++counts[static_cast<std::size_t>(b)];
  }
  Points points;
  for (int b = 0; b < bins; ++b) {
    points.emplace_back(lo + (b + 0.5) * width, counts[static_cast<std::size_t>(b)]);
  }
  const StageFigures& total = l.stages[net::kTotalLatencyStage];
  const double median_ms = total.median_s * 1e3, p95_ms = total.p95_s * 1e3;
  // The median and the p95 as vertical lines in the key, drawn over the bars.
  const int tallest = *std::max_element(counts.begin(), counts.end());
  const auto vertical = [tallest](double x) { return Points{{x, 0.0}, {x, tallest * 1.1}}; };
  gp << "set style fill solid 1.0 border -1\nset boxwidth " << width << " absolute\n"
     << "set yrange [0:" << tallest * 1.25 << "]\nset grid ytics\nset key top left opaque box\n"
     << "set xrange [" << std::min(lo, median_ms) - width << ":" << std::max(hi, p95_ms) + width
     << "]\n";
  gp << "plot '-' with boxes lc rgb '" << kLeftColour << "' title "
     << quoted(std::to_string(ms.size()) + " frames")
     << ", '-' with lines lw 2 dt 2 lc rgb '#000000' title "
     << quoted("median " + number(median_ms, 2) + " ms") << ", '-' with lines lw 2 dt 3 lc rgb '"
     << kRightColour << "' title " << quoted("p95 " + number(p95_ms, 2) + " ms") << "\n";
  gp.send1d(points);
  gp.send1d(vertical(median_ms));
  gp.send1d(vertical(p95_ms));
  end(gp);
}

void video_rate_plot(gnuplotio::Gnuplot& gp, const RecordingStatistics& s, const PlotFile& plot) {
  begin(gp, plot);
  gp << "set multiplot layout 2,1 title "
     << quoted("Video received per camera (" + number(s.window_s, 1) + " s windows, by arrival)")
     << " font ',12'\n"
     << "set grid\nset key top right opaque box\n";
  const bool any = !s.cameras[0].t.empty() || !s.cameras[1].t.empty();
  for (int panel = 0; panel < 2; ++panel) {
    time_axis(gp, s.duration_s, panel == 1);
    gp << "set ylabel " << quoted(panel == 0 ? "frames per second" : "MB/s of JPEG") << "\n";
    // From zero, with room at the top for the key.
    double top = 0.0;
    for (const CameraRate& c : s.cameras) {
      for (double v : panel == 0 ? c.fps : c.mb_per_s) top = std::max(top, v);
    }
    gp << "set yrange [0:" << (top > 0.0 ? 1.4 * top : 1.0) << "]\n";
    if (!any) {
      plot_nothing(gp, "no camera frames recorded");
      gp << "set ytics\n";
      continue;
    }
    gp << "plot ";
    for (std::size_t eye = 0; eye < 2; ++eye) {
      const CameraRate& c = s.cameras[eye];
      const std::string mean = panel == 0 ? number(c.fps_mean, 1) + " fps mean"
                                          : number(c.mb_per_s_mean, 3) + " MB/s mean";
      gp << (eye > 0 ? ", " : "") << (c.t.empty() ? "NaN" : "'-'")
         << " with linespoints pt 7 ps 0.5 lw 1.5 lc rgb '"
         << (eye == 0 ? kLeftColour : kRightColour) << "' title "
         << quoted(c.camera + (c.t.empty() ? ": no frames" : ": " + mean));
    }
    gp << "\n";
    for (const CameraRate& c : s.cameras) {
      if (c.t.empty()) continue;
      Points points(c.t.size());
      for (std::size_t k = 0; k < c.t.size(); ++k) {
        points[k] = {c.t[k], panel == 0 ? c.fps[k] : c.mb_per_s[k]};
      }
      gp.send1d(points);
    }
  }
  gp << "unset multiplot\n";
  end(gp);
}

void display_mode_plot(gnuplotio::Gnuplot& gp, const RecordingStatistics& s, const PlotFile& plot) {
  begin(gp, plot);
  gp << "set title "
     << quoted("Display mode: AR (live video) or VR (scene drawn from the robot's state), " +
               std::to_string(s.display.size()) + " switches")
     << "\n";
  time_axis(gp, s.duration_s, true);
  if (s.display.empty()) {
    plot_nothing(gp, "no AR/VR switches recorded");
    end(gp);
    return;
  }
  // Two step functions filling the band [0, 1]: each is 1 while its mode is shown. Before the
  // first switch the mode is not in the recording: left blank.
  Points ar, vr;
  for (const DisplaySwitch& d : s.display) {
    ar.emplace_back(d.t, d.mode == DisplayMode::kAr ? 1.0 : 0.0);
    vr.emplace_back(d.t, d.mode == DisplayMode::kVr ? 1.0 : 0.0);
  }
  const double end_s = std::max(s.duration_s, s.display.back().t);
  ar.emplace_back(end_s, ar.back().second);
  vr.emplace_back(end_s, vr.back().second);
  gp << "set yrange [0:1.25]\nunset ytics\nset key top right horizontal\n"
     << "plot '-' with fillsteps fs solid 0.75 noborder lc rgb '" << kArColour
     << "' title 'AR: live video', '-' with fillsteps fs solid 0.75 noborder lc rgb '" << kVrColour
     << "' title 'VR: video late or stopped'\n";
  gp.send1d(ar);
  gp.send1d(vr);
  end(gp);
}

}  // namespace

Result<std::vector<PlotFile>> write_recording_plots(const RecordingStatistics& statistics,
                                                    const std::string& dir,
                                                    const PlotOptions& options) {
  auto gnuplot = find_gnuplot(options.gnuplot);
  if (!gnuplot) return gnuplot.error();
  const auto file = [&dir](std::string_view name, std::string title, int height) {
    return PlotFile{std::string(name), std::move(title),
                    (std::filesystem::path(dir) / name).string(), kPlotWidthPx, height};
  };
  const int joints = static_cast<int>(std::max<std::size_t>(1, statistics.tracking.size()));
  std::vector<PlotFile> plots = {
      file(kTrackingErrorPlot, "Joint tracking error (commanded - measured) against time",
           kTrackingTitleHeightPx + kTrackingPanelHeightPx * joints),
      file(kLatencyStagesPlot, "Video latency per stage (median, stacked)", kPlotHeightPx),
      file(kLatencyTotalPlot, "Video latency capture -> decoded (distribution)", kPlotHeightPx),
      file(kVideoRatePlot, "Frames per second and MB/s of JPEG per camera", kPlotHeightPx),
      file(kDisplayModePlot, "AR / VR display mode against time", kDisplayPlotHeightPx),
  };
  auto process = GnuplotProcess::start(*gnuplot);
  if (!process) return process.error();
  gnuplotio::Gnuplot& gp = (*process)->gp();
  tracking_plot(gp, statistics, plots[0]);
  latency_stages_plot(gp, statistics, plots[1]);
  latency_total_plot(gp, statistics, plots[2]);
  video_rate_plot(gp, statistics, plots[3]);
  display_mode_plot(gp, statistics, plots[4]);
  if (Status s = (*process)->finish(); !s) return s.error();
  for (const PlotFile& p : plots) {
    std::error_code error;
    if (std::filesystem::file_size(p.path, error) == 0 || error) {
      return Error{"gnuplot did not write " + p.path};
    }
  }
  return plots;
}

}  // namespace telear::report
