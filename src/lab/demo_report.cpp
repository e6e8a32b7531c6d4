#include "telear/lab/demo_report.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "telear/core/number_format.hpp"
#include "telear/net/latency_stages.hpp"
#include "telear/net/latency_summary.hpp"
#include "telear/session/plan_collision.hpp"
#include "telear/vision/calibration_file.hpp"

namespace telear::lab {
namespace {

using net::percentile;

double mean(const std::vector<double>& v) {
  if (v.empty()) return 0.0;
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double max_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

std::string fixed(double v, int digits) {
  return core::format_fixed(v, digits);
}

nlohmann::json latency_json(const std::vector<double>& v) {
  return {{"p50_ms", percentile(v, 50) * 1e3},
          {"p99_ms", percentile(v, 99) * 1e3},
          {"samples", v.size()}};
}

double ratio(std::uint64_t numerator, std::uint64_t denominator) {
  return denominator > 0 ? static_cast<double>(numerator) / static_cast<double>(denominator) : 0.0;
}

// A plan's check: its first contact, or its smallest clearance to the workspace.
nlohmann::json check_json(const geometry::TrajectoryCheckReport& check) {
  nlohmann::json j;
  j["collision_free"] = check.collision_free();
  if (!check.collision_free()) {
    const geometry::PlanCollision& c = check.collisions.front();
    j["time_s"] = c.time_s;
    j["link"] = c.body;
    j["object"] = c.other;
    j["depth_m"] = c.depth_m;
    j["contacts"] = check.collisions.size();
  } else {
    const geometry::PlanClearance& m = check.min_workspace_clearance;
    j["min_clearance_m"] = std::isfinite(m.distance_m) ? nlohmann::json(m.distance_m) : nullptr;
    j["time_s"] = m.time_s;
    j["link"] = m.body;
    j["object"] = m.other;
  }
  return j;
}

}  // namespace

std::string demo_report_json(const DemoFacts& facts) {
  const Recording& r = facts.recording;
  nlohmann::json report;
  report["robot"] = {{"name", facts.robot}, {"dof", facts.dof}, {"tip_link", facts.tip_link}};
  report["calibration"] = nlohmann::json::parse(facts.calibration_json, nullptr, false);
  report["calibration_cached"] = facts.calibration_cached;
  if (!facts.registration_json.empty()) {
    report["registration"] = nlohmann::json::parse(facts.registration_json, nullptr, false);
  }
  nlohmann::json overlay;
  const char* eye_names[2] = {"left", "right"};
  for (int i = 0; i < 2; ++i) {
    overlay[eye_names[i]] = {{"rms_px_mean", mean(r.residuals.rms_px[i])},
                             {"rms_px_mean_at_rest", mean(r.residuals.rms_px_at_rest[i])},
                             {"rms_px_mean_moving", mean(r.residuals.rms_px_moving[i])},
                             {"max_px", max_of(r.residuals.max_px[i])},
                             {"checks", r.residuals.rms_px[i].size()},
                             {"checks_at_rest", r.residuals.rms_px_at_rest[i].size()},
                             {"checks_moving", r.residuals.rms_px_moving[i].size()},
                             {"marker_not_found", r.residuals.misses[i]},
                             {"last_miss", r.residuals.last_miss[i]}};
  }
  report["overlay_error_live"] = overlay;
  nlohmann::json latency;
  for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) {
    latency[net::kLatencyStages[i].key] = latency_json(r.latency.seconds[i]);
  }
  report["video"] = {{"resolution", facts.resolution},
                     {"camera_fps", facts.camera_fps},
                     {"frames_shown", r.frames_shown},
                     {"display_ticks", r.ticks},
                     {"fps_shown", facts.seconds > 0 ? r.frames_shown / facts.seconds : 0.0},
                     {"latency", latency},
                     {"bytes_per_s", facts.video_bytes_per_s}};
  report["bytes"] = {
      {"plan_message_measured", facts.plan_bytes_measured},
      {"plan_message", facts.plan_message_bytes},
      {"samples_100hz", facts.bytes.plan_bytes},
      {"jog_100hz", facts.bytes.jog_stream_bytes},
      {"jog_messages", facts.bytes.jog_messages},
      {"ratio", ratio(facts.bytes.jog_stream_bytes, facts.plan_bytes_measured)},
      {"ratio_vs_samples", ratio(facts.bytes.plan_bytes, facts.plan_bytes_measured)}};
  nlohmann::json tracking;
  tracking["result"] = facts.execution_result;
  if (facts.tracking) {
    tracking["max_error_rad"] = facts.tracking->max_error_so_far;
    tracking["max_error_joint"] = facts.tracking->max_error_joint + 1;
    tracking["rms_error_rad"] = facts.tracking->rms_error;
    tracking["samples"] = facts.tracking->samples;
    tracking["tolerance_rad"] = facts.tolerance_rad;
    tracking["max_command_deviation_rad"] = facts.tracking->max_command_deviation;
  }
  tracking["previewed_hash"] = facts.previewed_hash;
  tracking["executed_hash"] = facts.executed_hash;
  tracking["executed_is_previewed"] =
      !facts.executed_hash.empty() && facts.executed_hash == facts.previewed_hash;
  tracking["plan_duration_s"] = facts.plan_duration_s;
  tracking["waypoints"] = facts.waypoints;
  report["execution"] = tracking;
  nlohmann::json switches = nlohmann::json::array();
  for (const session::ModeSwitch& s : facts.switches) {
    switches.push_back(
        {{"from", to_string(s.from)}, {"to", to_string(s.to)}, {"reason", s.reason}});
  }
  report["display"] = {{"ar_to_vr", facts.ar_to_vr},
                       {"vr_to_ar", facts.vr_to_ar},
                       {"predicted_late_s", facts.predicted_late_s},
                       {"injected_delay_ms", facts.injected_delay_ms},
                       {"switches", switches}};
  if (const auto& p = facts.prediction) {
    report["prediction"] = {{"delay_ms", facts.injected_delay_ms},
                            {"frames", p->frames},
                            {"frames_predicted", p->frames_predicted},
                            {"horizon_ms_p50", p->horizon_ms_p50},
                            {"tool_error_mm_p50_predicted", p->predicted_mm_p50},
                            {"tool_error_mm_p95_predicted", p->predicted_mm_p95},
                            {"tool_error_mm_max_predicted", p->predicted_mm_max},
                            {"tool_error_mm_p50_unpredicted", p->unpredicted_mm_p50},
                            {"tool_error_mm_p95_unpredicted", p->unpredicted_mm_p95},
                            {"tool_error_mm_max_unpredicted", p->unpredicted_mm_max}};
  }
  if (!facts.mcap_json.empty()) {
    report["recording"] = nlohmann::json::parse(facts.mcap_json, nullptr, false);
    nlohmann::json plots = nlohmann::json::array();
    for (const auto& [file, title] : facts.plots) plots.push_back(file);
    report["recording"]["plots"] = plots;
    report["recording"]["summary"] = facts.recording_report_md;
    report["recording"]["plot_error"] = facts.plot_error;
  }
  report["outputs"] = {{"video", r.video_path},
                       {"video_codec", r.video_codec},
                       {"video_warning", r.video_warning},
                       {"video_frames", r.video_frames},
                       {"key_frames", r.key_frames}};
  if (facts.first_rehearsal_check || facts.final_plan_check) {
    nlohmann::json collision;
    if (facts.first_rehearsal_check)
      collision["first_rehearsal"] = check_json(*facts.first_rehearsal_check);
    if (facts.final_plan_check) collision["final_plan"] = check_json(*facts.final_plan_check);
    report["collision"] = collision;
  }
  report["seconds"] = facts.seconds;
  return report.dump(2) + "\n";
}

std::string demo_report_markdown(const DemoFacts& facts) {
  const Recording& r = facts.recording;
  std::string md =
      "# telear demo report\n\n"
      "Pick-and-place rehearsed on the ghost over the simulated stereo video, previewed, "
      "executed on the simulated robot (" +
      facts.robot + ", " + std::to_string(facts.dof) +
      " joints) as one trajectory and monitored.\n\n"
      "| | left | right |\n|---|---|---|\n";
  const nlohmann::json eval = nlohmann::json::parse(facts.calibration_json, nullptr, false);
  if (eval.is_object() && eval.contains("left") && eval.contains("right")) {
    for (const char* key : {"fx_error_percent", "cx_error_px", "cy_error_px", "registration_mm",
                            "registration_deg", "overlay_rms_px"}) {
      md += std::string("| calibration ") + key + " | " + fixed(eval["left"].value(key, 0.0), 3) +
            " | " + fixed(eval["right"].value(key, 0.0), 3) + " |\n";
    }
  }
  const nlohmann::json registration =
      nlohmann::json::parse(facts.registration_json, nullptr, false);
  if (registration.is_object() && registration.contains("left")) {
    md += "| registration through the servers (" +
          std::to_string(registration.value("poses_used", 0)) + " poses), Shah-Li mm | " +
          fixed(registration["left"].value("shah_li_mm", 0.0), 3) + " | " +
          fixed(registration["right"].value("shah_li_mm", 0.0), 3) + " |\n";
  }
  md += "| live overlay error (marker), mean RMS px | " + fixed(mean(r.residuals.rms_px[0]), 3) +
        " | " + fixed(mean(r.residuals.rms_px[1]), 3) + " |\n";
  md += "| ... with the arm at rest / moving | " + fixed(mean(r.residuals.rms_px_at_rest[0]), 3) +
        " / " + fixed(mean(r.residuals.rms_px_moving[0]), 3) + " | " +
        fixed(mean(r.residuals.rms_px_at_rest[1]), 3) + " / " +
        fixed(mean(r.residuals.rms_px_moving[1]), 3) + " |\n\n";
  md += "| stage | p50 ms | p99 ms |\n|---|---|---|\n";
  for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) {
    const std::vector<double>& series = r.latency.seconds[i];
    md += std::string("| ") + net::kLatencyStages[i].label + " | " +
          fixed(percentile(series, 50) * 1e3, 2) + " | " + fixed(percentile(series, 99) * 1e3, 2) +
          " |\n";
  }
  md += "\n- video: " + facts.resolution + " stereo, " + std::to_string(r.frames_shown) +
        " frames shown";
  if (!r.video_codec.empty()) md += ", " + r.video_codec;
  md += "\n";
  if (!r.video_warning.empty()) md += "- warning: " + r.video_warning + "\n";
  md += "- bytes to command the motion: the plan message " +
        std::to_string(facts.plan_bytes_measured) + " B, its 100 Hz samples " +
        std::to_string(facts.bytes.plan_bytes) + " B (" +
        fixed(ratio(facts.bytes.plan_bytes, facts.plan_bytes_measured), 1) +
        "x), jogging at 100 Hz " + std::to_string(facts.bytes.jog_stream_bytes) + " B (" +
        std::to_string(facts.bytes.jog_messages) + " messages, " +
        fixed(ratio(facts.bytes.jog_stream_bytes, facts.plan_bytes_measured), 1) +
        "x)\n- execution: " + facts.execution_result;
  if (facts.tracking) {
    md += ", max tracking error " + fixed(facts.tracking->max_error_so_far * 1e3, 3) +
          " mrad (tolerance " + fixed(facts.tolerance_rad * 1e3, 0) + " mrad)";
  }
  const bool same = !facts.executed_hash.empty() && facts.executed_hash == facts.previewed_hash;
  md += std::string("\n- executed the previewed trajectory: ") + (same ? "yes" : "NO") +
        " (plan hash " + facts.executed_hash.substr(0, 16) + "...";
  if (facts.tracking) {
    md += ", robot's command within " + fixed(facts.tracking->max_command_deviation * 1e3, 4) +
          " mrad of the preview";
  }
  md += ")";
  if (facts.first_rehearsal_check && facts.final_plan_check) {
    md += "\n- collision: the first rehearsal, " +
          session::collision_summary(*facts.first_rehearsal_check) + "; the executed plan, " +
          session::collision_summary(*facts.final_plan_check);
  }
  md += "\n- display: " + std::to_string(facts.ar_to_vr) + " AR -> VR and " +
        std::to_string(facts.vr_to_ar) + " VR -> AR switches (injected delay " +
        std::to_string(facts.injected_delay_ms) + " ms); " + fixed(facts.predicted_late_s, 1) +
        " s of late video kept in AR by the predicted arm\n";
  if (const auto& p = facts.prediction) {
    md += "- predicted arm, while the states were late too (" + std::to_string(p->frames) +
          " frames, " + std::to_string(p->frames_predicted) + " predicted " +
          fixed(p->horizon_ms_p50, 0) + " ms ahead): tool error against the truth p50 / p95 " +
          fixed(p->predicted_mm_p50, 2) + " / " + fixed(p->predicted_mm_p95, 2) +
          " mm, without prediction " + fixed(p->unpredicted_mm_p50, 1) + " / " +
          fixed(p->unpredicted_mm_p95, 1) + " mm\n";
  }
  md += "- total " + fixed(facts.seconds, 1) + " s\n";
  // The recording's plots (`telear report`), drawn into the same folder.
  if (!facts.plots.empty() || !facts.plot_error.empty()) {
    md += "\n## Plots of the recording\n\n";
    if (!facts.recording_report_md.empty()) {
      md += "The task's MCAP recording as `telear report` plots it; its figures and events: [" +
            facts.recording_report_md + "](" + facts.recording_report_md + ").\n";
    }
    if (facts.plots.empty()) md += "\nPlots not drawn: " + facts.plot_error + ".\n";
    for (const auto& [file, title] : facts.plots) md += "\n![" + title + "](" + file + ")\n";
  }
  return md;
}

Status write_demo_report(const DemoFacts& facts, const std::string& out_dir) {
  return vision::write_files_atomically({{out_dir + "/report.json", demo_report_json(facts)},
                                         {out_dir + "/report.md", demo_report_markdown(facts)}});
}

}  // namespace telear::lab
