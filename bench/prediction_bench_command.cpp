#include "bench/prediction_bench_command.hpp"

#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <ostream>
#include <thread>

#include "bench/json_file.hpp"
#include "bench/quiet_log.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/lab/prediction_error.hpp"
#include "telear/session/session.hpp"

namespace telear::cli {

namespace {

// The goal at 400 ms.
constexpr double kGoalP95Mm = 2.0;
constexpr double kGoalRatio = 10.0;

// The plan, degrees: the demo's ready pose (parked beside the table, docs/demo.md), then moves
// of every joint at once -- the turn to the table and reaches over it.
constexpr double kWaypointsDeg[4][6] = {{-90, 30, -120, 0, -45, 0},
                                        {-20, 45, -100, 30, -65, 40},
                                        {15, 20, -75, -25, -30, -35},
                                        {-45, 40, -115, 10, -55, 20}};

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

Eigen::VectorXd waypoint(int k) {
  Eigen::VectorXd q(6);
  for (int j = 0; j < 6; ++j) q[j] = core::radians_from_degrees(kWaypointsDeg[k][j]);
  return q;
}

struct Measured {
  lab::PredictionErrorSummary errors;
  double plan_duration_s = 0.0;
  std::string result;  // the execution's
};

// Ticks the session at `fps` until `done` or `timeout_s`; `each` runs before every update.
template <typename Done, typename Each>
bool tick_until(session::Session& session, double fps, double timeout_s, Done done, Each each) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto period = std::chrono::duration<double>(1.0 / fps);
  auto next = start;
  while (!done()) {
    if (std::chrono::duration<double>(Clock::now() - start).count() > timeout_s) return false;
    each();
    session.update(period.count());
    next += std::chrono::duration_cast<Clock::duration>(period);
    std::this_thread::sleep_until(next);
  }
  return true;
}

Result<Measured> measure(const PredictionBenchOptions& options) {
  auto model = core::load_robot("puma560");
  if (!model) return model.error();
  lab::EmbeddedServersOptions server_options;
  server_options.fps = options.camera_fps;
  server_options.initial_q = waypoint(0);
  auto servers = lab::EmbeddedServers::create(*model, server_options);
  if (!servers) return servers.error();
  sim::SimulatedRobot& truth = (*servers)->driver().robot();

  const double delay_s = options.delay_ms / 1000.0;
  session::SessionOptions session_options;
  session_options.robot.address = (*servers)->robot_address();
  session_options.robot.token = (*servers)->token();
  session_options.robot.client_name = "bench-prediction";
  session_options.vision.address = (*servers)->vision_address();
  session_options.vision.token = (*servers)->token();
  session_options.vision.client_name = "bench-prediction";
  session_options.lease_heartbeat_s = 1.0;  // this machine also renders the cameras
  session_options.injected_video_delay_s = delay_s;
  session_options.injected_state_delay_s = delay_s;
  auto created = session::Session::create(*model, session_options);
  if (!created) return created.error();
  session::Session& session = **created;
  session.connect();
  // Connected: a state and a frame through the delay.
  if (!tick_until(
          session, options.fps, 20.0 + delay_s,
          [&] { return session.view().real.has_value() && session.view().frame != nullptr; },
          [] {})) {
    return Error{"no robot state and video frame from the embedded servers within " +
                 format("%.0f", 20.0 + delay_s) + " s"};
  }
  if (Status s = session.take_control(); !s) return s.error();

  session::Plan& plan = session.plan();
  if (Status s = plan.set_scales(options.speed, options.speed); !s) return s.error();
  for (int k = 0; k <= options.moves; ++k) {
    if (Status s = plan.add({waypoint(k)}); !s) return s.error();
  }
  auto executed = session.execute_plan();
  if (!executed) return executed.error();
  Measured measured;
  measured.plan_duration_s = executed->duration_s;
  // The truth is read just before each update: the prediction is for the update's time.
  lab::PredictionErrorSeries series(**model);
  Eigen::VectorXd true_q;
  bool first = true;
  const bool finished = tick_until(
      session, options.fps, measured.plan_duration_s + delay_s + 20.0,
      [&] {
        if (!first) series.add(session.view(), true_q);
        first = false;
        return !session.executing();
      },
      [&] { true_q = truth.state().q; });
  if (!finished) return Error{"the plan did not finish in time"};
  measured.result = session.last_execution_result();
  measured.errors = series.summary();
  session.disconnect();
  (*servers)->stop();
  return measured;
}

}  // namespace

int run_bench_prediction(const PredictionBenchOptions& options, std::ostream& out,
                         std::ostream& err) {
  const auto fail = [&err](const std::string& message, int code) {
    err << "telear bench prediction: " << message << "\n";
    return code;
  };
  if (options.delay_ms < 0 || options.delay_ms > 5000) {
    return fail("--delay-ms must be in 0..5000, got " + std::to_string(options.delay_ms), 2);
  }
  if (options.moves < 1 || options.moves > 3) {
    return fail("--moves must be in 1..3, got " + std::to_string(options.moves), 2);
  }
  if (!(options.speed > 0 && options.speed <= 1)) {
    return fail("--speed must be in (0, 1], got " + format("%g", options.speed), 2);
  }
  if (!(options.fps >= 1 && options.fps <= 120)) {
    return fail("--fps must be in 1..120, got " + format("%g", options.fps), 2);
  }
  if (!(options.camera_fps > 0 && options.camera_fps <= 60)) {
    return fail("--camera-fps must be in (0, 60], got " + format("%g", options.camera_fps), 2);
  }
  std::ofstream json_file;
  if (const auto error = open_json_file(options.json, json_file)) return fail(*error, 2);

  const QuietLog quiet;
  const auto wall_start = std::chrono::steady_clock::now();
  out << "telear bench prediction: the simulated PUMA 560 through the embedded servers, video "
         "and state held back by "
      << options.delay_ms << " ms, " << options.moves << " moves at " << format("%g", options.speed)
      << " of the limits, the view at " << format("%g", options.fps) << " fps\n";
  auto measured = measure(options);
  if (!measured) return fail(measured.error().message, 1);
  const lab::PredictionErrorSummary& e = measured->errors;
  const double ratio = e.predicted_mm_p95 > 0 ? e.unpredicted_mm_p95 / e.predicted_mm_p95 : 0.0;
  const bool goal = e.predicted_mm_p95 <= kGoalP95Mm && ratio >= kGoalRatio;
  out << "plan " << format("%.2f", measured->plan_duration_s) << " s, execution "
      << measured->result << "; " << e.frames << " frames measured, " << e.frames_predicted
      << " with the predicted arm (predicting " << format("%.0f", e.horizon_ms_p50)
      << " ms ahead, median)\n";
  out << "| tool error against the truth (mm) | p50 | p95 | max |\n|---|---|---|---|\n";
  out << "| predicted (Smith) | " << format("%.2f", e.predicted_mm_p50) << " | "
      << format("%.2f", e.predicted_mm_p95) << " | " << format("%.2f", e.predicted_mm_max)
      << " |\n";
  out << "| without prediction (last reported state) | " << format("%.2f", e.unpredicted_mm_p50)
      << " | " << format("%.2f", e.unpredicted_mm_p95) << " | "
      << format("%.2f", e.unpredicted_mm_max) << " |\n";
  out << "p95 without / with prediction " << format("%.1f", ratio)
      << "x; goal (p95 <= " << format("%.0f", kGoalP95Mm)
      << " mm and >= " << format("%.0f", kGoalRatio) << "x smaller) " << (goal ? "met" : "not met")
      << "\n";
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  out << "ran in " << format("%.1f", seconds) << " s\n";

  if (json_file) {
    nlohmann::json j;
    j["delay_ms"] = options.delay_ms;
    j["moves"] = options.moves;
    j["speed"] = options.speed;
    j["fps"] = options.fps;
    j["plan_duration_s"] = measured->plan_duration_s;
    j["execution"] = measured->result;
    j["frames"] = e.frames;
    j["frames_predicted"] = e.frames_predicted;
    j["horizon_ms_p50"] = e.horizon_ms_p50;
    j["tool_error_mm_p50_predicted"] = e.predicted_mm_p50;
    j["tool_error_mm_p95_predicted"] = e.predicted_mm_p95;
    j["tool_error_mm_max_predicted"] = e.predicted_mm_max;
    j["tool_error_mm_p50_unpredicted"] = e.unpredicted_mm_p50;
    j["tool_error_mm_p95_unpredicted"] = e.unpredicted_mm_p95;
    j["tool_error_mm_max_unpredicted"] = e.unpredicted_mm_max;
    j["p95_ratio"] = ratio;
    j["goal"] = {{"p95_mm", kGoalP95Mm}, {"ratio", kGoalRatio}, {"met", goal}};
    j["seconds"] = seconds;
    json_file << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace telear::cli
