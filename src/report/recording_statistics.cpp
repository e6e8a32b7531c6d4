#include "telear/report/recording_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "telear/core/robot_description.hpp"
#include "telear/net/latency_summary.hpp"

namespace telear::report {
namespace {

constexpr double kNsPerS = 1e9;

std::vector<JointTrackingError> tracking_errors(const record::RecordingSeries& series,
                                                std::size_t& paired) {
  const record::JointSeries& robot = series.robot;
  const record::JointSeries& commands = series.commands;
  std::vector<JointTrackingError> joints;
  paired = 0;
  if (robot.samples.empty() || commands.samples.empty() || robot.names != commands.names) {
    return joints;
  }
  const std::vector<JointUnit> units = joint_units(series, robot.names);
  for (std::size_t i = 0; i < robot.names.size(); ++i) {
    joints.push_back({robot.names[i], units[i], {}, {}, 0.0, 0.0});
  }
  for (const record::JointSample& measured : robot.samples) {
    // The command the recorder wrote with this state: same log time, same stamp.
    const record::JointSample* command = commands.at(measured.log_ns);
    if (command == nullptr || command->log_ns != measured.log_ns ||
        command->stamp_ns != measured.stamp_ns) {
      continue;
    }
    ++paired;
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      const double e = (command->position[k] - measured.position[k]) * joints[i].unit.per_si;
      if (!std::isfinite(e)) continue;
      joints[i].t.push_back(measured.t);
      joints[i].error.push_back(e);
    }
  }
  for (JointTrackingError& j : joints) {
    double sum_squares = 0.0;
    for (double e : j.error) {
      sum_squares += e * e;
      j.max_abs = std::max(j.max_abs, std::abs(e));
    }
    if (!j.error.empty()) j.rms = std::sqrt(sum_squares / static_cast<double>(j.error.size()));
  }
  return joints;
}

double median(std::vector<double> v) {
  return net::percentile(std::move(v), 50);
}

LatencyFigures latency_figures(const record::RecordingSeries& series, double duration_s,
                               int windows) {
  LatencyFigures f;
  std::array<std::vector<double>, net::kLatencyStageCount> stages;
  for (const record::LatencySample& s : series.latency) {
    for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) stages[i].push_back(s.stages[i]);
  }
  for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) {
    f.stages[i] = {net::percentile(stages[i], 50), net::percentile(stages[i], 95),
                   stages[i].size()};
  }
  f.total_s = stages[net::kTotalLatencyStage];
  if (series.latency.empty() || windows < 1) return f;
  const double width = std::max(duration_s, 1e-9) / windows;
  for (int w = 0; w < windows; ++w) {
    LatencyWindow window;
    window.start_s = w * width;
    window.end_s = (w + 1) * width;
    std::array<std::vector<double>, net::kLatencyStageCount> in;
    for (const record::LatencySample& s : series.latency) {
      // The last window includes the recording's end.
      if (s.t < window.start_s || (s.t >= window.end_s && w + 1 < windows)) continue;
      for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) in[i].push_back(s.stages[i]);
    }
    window.samples = in[0].size();
    if (window.samples == 0) continue;
    for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) window.median_s[i] = median(in[i]);
    f.windows.push_back(window);
  }
  return f;
}

CameraRate camera_rate(const std::vector<record::FrameSample>& frames, std::string camera,
                       double window_s) {
  CameraRate rate;
  rate.camera = std::move(camera);
  rate.frames = frames.size();
  for (const record::FrameSample& f : frames) rate.bytes += f.bytes;
  if (frames.size() < 2) return rate;
  const double first = frames.front().t, last = frames.back().t;
  if (last > first) {
    rate.fps_mean = static_cast<double>(frames.size() - 1) / (last - first);
    rate.mb_per_s_mean = static_cast<double>(rate.bytes) / (last - first) / 1e6;
  }
  // Windows from the first frame to one frame interval past the last (the last frame's own
  // interval: n frames at a steady rate fill n intervals). A last window shorter than half of
  // one is left out, its rate resting on a frame or two.
  const double stop = last + (last - first) / static_cast<double>(frames.size() - 1);
  std::size_t k = 0;
  for (double start = first; start < stop; start += window_s) {
    const double end = std::min(start + window_s, stop);
    if (end - start < 0.5 * window_s && !rate.t.empty()) break;
    std::size_t n = 0;
    std::uint64_t bytes = 0;
    for (; k < frames.size() && frames[k].t < start + window_s; ++k) {
      ++n;
      bytes += frames[k].bytes;
    }
    rate.t.push_back(0.5 * (start + end));
    rate.fps.push_back(static_cast<double>(n) / (end - start));
    rate.mb_per_s.push_back(static_cast<double>(bytes) / (end - start) / 1e6);
  }
  return rate;
}

std::vector<DisplaySwitch> display_switches(const record::RecordingSeries& series) {
  std::vector<DisplaySwitch> switches;
  for (const record::PlanEventSample& e : series.plan_events) {
    if (e.kind_name != "DISPLAY_MODE") continue;
    const std::string mode = e.text.substr(0, 2);
    if (mode == "ar" || mode == "AR") switches.push_back({e.t, DisplayMode::kAr, e.text});
    if (mode == "vr" || mode == "VR") switches.push_back({e.t, DisplayMode::kVr, e.text});
  }
  return switches;
}

}  // namespace

std::vector<JointUnit> joint_units(const record::RecordingSeries& series,
                                   const std::vector<std::string>& joints) {
  std::vector<JointUnit> units(joints.size());
  if (series.urdf.empty()) return units;
  std::string tip;
  if (const auto session = series.metadata.find("telear.session");
      session != series.metadata.end()) {
    if (const auto t = session->second.find("tip_link"); t != session->second.end()) {
      tip = t->second;
    }
  }
  auto description = core::parse_urdf_description(series.urdf, "the recording's robot.urdf", tip);
  if (!description) return units;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    for (const core::Joint& j : description->model->joints()) {
      if (j.name != joints[i]) continue;
      units[i] = j.type == core::JointType::kPrismatic ? JointUnit{"mm", 1e3}
                                                       : JointUnit{"deg", 180.0 / std::numbers::pi};
    }
  }
  return units;
}

RecordingStatistics recording_statistics(const record::RecordingSeries& series,
                                         const StatisticsOptions& options) {
  RecordingStatistics s;
  s.duration_s = static_cast<double>(series.end_ns - series.start_ns) / kNsPerS;
  s.window_s = options.window_s;
  s.tracking = tracking_errors(series, s.tracking_samples);
  s.latency = latency_figures(series, s.duration_s, options.latency_windows);
  const char* cameras[2] = {"left", "right"};
  for (std::size_t eye = 0; eye < 2; ++eye) {
    s.cameras[eye] = camera_rate(series.frames[eye], cameras[eye], options.window_s);
  }
  s.display = display_switches(series);
  if (const auto recording = series.metadata.find("telear.recording");
      recording != series.metadata.end()) {
    constexpr std::string_view kDropped = "dropped ";
    for (const auto& [key, value] : recording->second) {
      // Counts the recorder wrote itself: a value that is not a number is left out.
      char* end = nullptr;
      const std::uint64_t n = std::strtoull(value.c_str(), &end, 10);
      if (end == value.c_str() || *end != '\0') continue;
      if (key == "dropped_total") s.dropped_total = n;
      if (key.starts_with(kDropped)) s.dropped[key.substr(kDropped.size())] = n;
    }
  }
  return s;
}

}  // namespace telear::report
