#pragma once
// The plots of `telear report` (docs/recording.md, "Plots: telear report"): PNG files drawn by
// gnuplot (Debian's gnuplot-nox, its pngcairo terminal) from a recording's figures
// (recording_statistics.hpp). gnuplot runs as one child process for all of them; the data go
// to it inline through its standard input (gnuplot-iostream), so no data file is written.
//
//   tracking_error.png    commanded - measured against time, one panel per joint, in the
//                         joint's unit (deg, mm, or rad where the URDF says nothing)
//   latency_stages.png    the median of each latency stage as a stacked bar, for the whole
//                         recording and for consecutive time windows
//   latency_total.png     the histogram of each frame's capture -> decoded latency, its median
//                         and p95 marked
//   video_rate.png        frames per second and MB/s of JPEG against time, per camera
//   display_mode.png      AR (live video) and VR (drawn from the robot's state) on the time axis
//
// A plot whose data the recording lacks is still drawn, with its axes and a line saying what is
// missing ("no AR/VR switches recorded"), so a report always has the same files.

#include <string>
#include <string_view>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/report/recording_statistics.hpp"

namespace telear::report {

inline constexpr std::string_view kTrackingErrorPlot = "tracking_error.png";
inline constexpr std::string_view kLatencyStagesPlot = "latency_stages.png";
inline constexpr std::string_view kLatencyTotalPlot = "latency_total.png";
inline constexpr std::string_view kVideoRatePlot = "video_rate.png";
inline constexpr std::string_view kDisplayModePlot = "display_mode.png";

// Sizes in pixels: every plot kPlotWidthPx wide; the tracking plot kTrackingTitleHeightPx plus
// kTrackingPanelHeightPx per joint (one panel when there is no joint), the display mode plot
// kDisplayPlotHeightPx, the others kPlotHeightPx.
inline constexpr int kPlotWidthPx = 1000;
inline constexpr int kPlotHeightPx = 450;
inline constexpr int kDisplayPlotHeightPx = 260;
inline constexpr int kTrackingPanelHeightPx = 170;
inline constexpr int kTrackingTitleHeightPx = 50;

struct PlotOptions {
  // gnuplot: a name looked up on PATH, or a path.
  std::string gnuplot = "gnuplot";
};

struct PlotFile {
  std::string name;   // kTrackingErrorPlot, ...
  std::string title;  // what it shows, for the summary's caption
  std::string path;   // dir/name
  int width_px = 0, height_px = 0;
};

// Writes the five plots into `dir` (an existing folder), in the order above. Errors: gnuplot
// not found ("gnuplot not found (apt-get install gnuplot-nox)"), gnuplot failed (what it said),
// a plot it did not write.
Result<std::vector<PlotFile>> write_recording_plots(const RecordingStatistics& statistics,
                                                    const std::string& dir,
                                                    const PlotOptions& options = {});

}  // namespace telear::report
