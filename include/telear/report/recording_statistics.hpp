#pragma once
// The figures `telear report` plots and summarizes, computed from a recording's series
// (record::RecordingSeries). Everything here is plain arithmetic on the series (no gnuplot), so
// the numbers in the plots and in the Markdown are the same ones, and tests check them directly.
//
//   tracking error   per joint, commanded - measured: each /robot/joint_states sample with the
//                    /robot/joint_commands sample of the same state (same log time and stamp,
//                    the recorder writes both from one RobotState). Degrees for a revolute joint,
//                    millimetres for a prismatic one (the joint's type in the recording's URDF);
//                    radians, labelled so, when the URDF is missing or does not name the joint.
//                    RMS = sqrt(mean(e^2)), max = max |e|.
//   latency          per stage of net::kLatencyStages: median and p95 (nearest rank, as every
//                    latency figure of telear: net/latency_summary.hpp) over /telear/latency;
//                    the same medians in consecutive time windows (the stacked bars).
//   video rate       per camera, frames per second and MB/s of JPEG (1 MB = 1e6 bytes) in
//                    consecutive windows of `window_s` by log time (arrival at the recorder);
//                    the mean of each from the first frame to the last.
//   display mode     /telear/plan_events of kind DISPLAY_MODE whose text starts "ar" or "vr"
//                    (session/display_mode.hpp's switches: AR = live video, VR = the scene drawn
//                    from the robot's reported state).
//   drops            the "telear.recording" metadata SessionRecorder writes when it closes.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "telear/net/latency_stages.hpp"
#include "telear/record/recording_series.hpp"

namespace telear::report {

// A joint's values in the report's unit: value = si_value * per_si (si: rad or m).
struct JointUnit {
  std::string name = "rad";  // "deg", "mm" or "rad"
  double per_si = 1.0;
};

struct JointTrackingError {
  std::string joint;
  JointUnit unit;
  std::vector<double> t;      // s since the recording's start
  std::vector<double> error;  // commanded - measured, in `unit`
  double rms = 0.0;           // in `unit`; 0 without samples
  double max_abs = 0.0;
};

struct StageFigures {
  double median_s = 0.0, p95_s = 0.0;  // 0 without samples
  std::size_t samples = 0;
};

// The medians of each stage over the frames whose log time is in [start_s, end_s).
struct LatencyWindow {
  double start_s = 0.0, end_s = 0.0;
  std::size_t samples = 0;
  std::array<double, net::kLatencyStageCount> median_s{};
};

struct LatencyFigures {
  std::array<StageFigures, net::kLatencyStageCount> stages;  // kLatencyStages' order
  std::vector<double> total_s;                               // every frame's total
  std::vector<LatencyWindow> windows;                        // only windows with frames
};

struct CameraRate {
  std::string camera;  // "left", "right"
  std::size_t frames = 0;
  std::uint64_t bytes = 0;
  double fps_mean = 0.0;       // (frames - 1) / (last - first); 0 under two frames
  double mb_per_s_mean = 0.0;  // bytes / (last - first) / 1e6
  // Per window: its centre (s), frames per second, MB/s of JPEG.
  std::vector<double> t, fps, mb_per_s;
};

enum class DisplayMode { kAr, kVr };

struct DisplaySwitch {
  double t = 0.0;
  DisplayMode mode = DisplayMode::kAr;
  std::string text;  // the event's text ("vr: video 512 ms late", ...)
};

struct RecordingStatistics {
  double duration_s = 0.0;
  double window_s = 1.0;  // the video rate's windows (StatisticsOptions::window_s)
  std::vector<JointTrackingError> tracking;  // one per arm joint; empty without commands
  std::size_t tracking_samples = 0;          // states paired with their command
  LatencyFigures latency;
  std::array<CameraRate, 2> cameras;  // left, right
  std::vector<DisplaySwitch> display;
  // Items the recorder dropped, per topic (its queue was full), and their total; absent when
  // the file has no telear.recording metadata (the recorder was killed before it closed).
  std::map<std::string, std::uint64_t> dropped;
  std::optional<std::uint64_t> dropped_total;
};

struct StatisticsOptions {
  double window_s = 1.0;    // the video rate's windows, > 0
  int latency_windows = 6;  // the stacked bars over time, >= 1 (besides the whole recording)
};

// The unit of each of `joints` from the recording's URDF (series.urdf, the chain to the
// telear.session metadata's tip_link); radians for every joint when it does not parse.
std::vector<JointUnit> joint_units(const record::RecordingSeries& series,
                                   const std::vector<std::string>& joints);

RecordingStatistics recording_statistics(const record::RecordingSeries& series,
                                         const StatisticsOptions& options = {});

}  // namespace telear::report
