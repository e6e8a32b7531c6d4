#pragma once
// The demo's report (docs/demo.md, "Outputs"): report.json (machine-readable) and report.md
// (the same figures as tables), from what the demo measured.
//
// report.json's keys: robot.{name, dof, tip_link}, calibration (eval.json,
// include/telear/vision/accuracy_check.hpp), calibration_cached, registration.{path,
// capture_dir, poses_requested, poses_captured, poses_used, frames_per_pose, capture_s, seconds,
// sigma_mm, sigma_deg, left/right.{registration_mm, registration_deg, overlay_rms_px,
// shah_li_mm, shah_li_deg}} (absent without one),
// overlay_error_live.{left,right}.{rms_px_mean, max_px, checks, marker_not_found, last_miss},
// video.{resolution, camera_fps, frames_shown, display_ticks, fps_shown, latency.<stage>.{p50_ms,
// p99_ms, samples}, bytes_per_s}, bytes.{plan_message_measured, plan_message, samples_100hz,
// jog_100hz, jog_messages, ratio (jogs / plan message), ratio_vs_samples}, execution.{result,
// max_error_rad, max_error_joint (1-based), rms_error_rad, samples, tolerance_rad,
// max_command_deviation_rad, plan_duration_s, waypoints, previewed_hash, executed_hash,
// executed_is_previewed}, display.{ar_to_vr, vr_to_ar, predicted_late_s,
// injected_delay_ms, switches}, prediction.{delay_ms, frames, frames_predicted, horizon_ms_p50,
// tool_error_mm_p50_predicted, tool_error_mm_p95_predicted, tool_error_mm_max_predicted, the
// same _unpredicted} (the delay window's states late, against the simulator's truth; absent
// without one), recording.{path, messages.<topic>, dropped, bytes, plots (PNG file
// names), summary (recording_report.md), plot_error} (absent without a recording), outputs.{video,
// video_codec, video_warning, video_frames, key_frames}, collision.{first_rehearsal,
// final_plan}.{collision_free, time_s, link, object, depth_m (the first contact) | min_clearance_m,
// link, object (the workspace clearance)} (absent without a collision check), seconds. Latency
// stages: the keys of net::kLatencyStages (include/telear/net/latency_stages.hpp),
// capture_to_encode, encode, send_queue, network, decode, total (nearest-rank percentiles).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/lab/prediction_error.hpp"
#include "telear/lab/session_recorder.hpp"
#include "telear/net/command_bytes.hpp"
#include "telear/session/display_mode.hpp"
#include "telear/session/execution_monitor.hpp"

namespace telear::lab {

struct DemoFacts {
  std::string robot;  // the robot file's name (puma560, ur6, arm7)
  int dof = 0;
  std::string tip_link;          // empty for a DH robot
  std::string calibration_json;  // eval.json's text
  bool calibration_cached = false;
  // The registration through the servers (a JSON object: poses, mm / deg against the truth,
  // Shah-Li's beside it, seconds); empty: none.
  std::string registration_json;
  Recording recording;
  // The MCAP recording of the task (--record; a JSON object: path, messages per topic,
  // dropped, bytes); empty: none.
  std::string mcap_json;
  // The recording's plots and summary (report::write_recording_report) in the output folder,
  // linked from report.md: file names and titles, the summary's name; plot_error says why there
  // are none (no gnuplot, or the recording could not be read).
  std::vector<std::pair<std::string, std::string>> plots;  // file name, title
  std::string recording_report_md;
  std::string plot_error;
  std::string resolution;  // "WxH" as given
  double camera_fps = 0.0;
  double video_bytes_per_s = 0.0;
  std::uint64_t plan_bytes_measured = 0;  // the plan message execute_plan sent
  std::uint64_t plan_message_bytes = 0;   // its size, computed
  net::CommandBytes bytes;                // the 100 Hz samples and jogs of the same motion
  std::string previewed_hash, executed_hash;
  std::string execution_result;
  std::optional<session::TrackingStatus> tracking;  // when the session monitored the execution
  double tolerance_rad = 0.0;
  double plan_duration_s = 0.0;
  int waypoints = 0;
  int ar_to_vr = 0;
  int vr_to_ar = 0;
  double predicted_late_s = 0.0;  // AR on late video, the arm predicted (display_mode.hpp)
  std::vector<session::ModeSwitch> switches;
  int injected_delay_ms = 0;
  // The predicted and the delayed arm's tool against the truth while the states were late.
  std::optional<PredictionErrorSummary> prediction;
  double seconds = 0.0;  // the whole demo so far
  // The collision checks of the first rehearsal (into the table) and of the executed plan,
  // when the session checked collisions.
  std::optional<geometry::TrajectoryCheckReport> first_rehearsal_check;
  std::optional<geometry::TrajectoryCheckReport> final_plan_check;
};

std::string demo_report_json(const DemoFacts& facts);
std::string demo_report_markdown(const DemoFacts& facts);
// OUT/report.json and OUT/report.md, all or nothing.
Status write_demo_report(const DemoFacts& facts, const std::string& out_dir);

}  // namespace telear::lab
