#include "telear/web/browser_operator.hpp"

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <sstream>

#include "telear/console/console_actions.hpp"
#include "telear/console/ui_script.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/robot_state.hpp"
#include "telear/net/latency_stages.hpp"
#include "telear/session/display_mode.hpp"

namespace telear::web {

namespace {

using nlohmann::json;

constexpr double kUpdatePeriodS = 1.0 / 60.0;  // the session's update, as the console's frame
constexpr double kStatePeriodS = 1.0 / 30.0;   // the page's state
constexpr double kShownWindowS = 2.0;          // capture -> shown statistics, as the console's

json degrees(const Eigen::VectorXd& q) {
  json out = json::array();
  for (Eigen::Index i = 0; i < q.size(); ++i) out.push_back(core::degrees_from_radians(q[i]));
  return out;
}

// What a refused connection says to the operator: the server's reason without the call's name
// ("get info: wrong token" -> "wrong token").
std::string refusal_reason(const std::string& message) {
  for (const char* prefix : {"get info: ", "get camera info: "}) {
    if (message.rfind(prefix, 0) == 0) return message.substr(std::string(prefix).size());
  }
  return message;
}

// Why an action line is not run from the page, or empty when it is.
std::string not_in_the_page(console::ActionKind kind) {
  using console::ActionKind;
  switch (kind) {
    case ActionKind::kConnect:
    case ActionKind::kDisconnect:
      return "the page connects with its token field and Connect button";
    case ActionKind::kPlanSave:
    case ActionKind::kPlanLoad:
      return "files on the machine running telear web are not reachable from the page";
    case ActionKind::kCaptureOpen:
    case ActionKind::kCaptureAdd:
    case ActionKind::kCaptureSolve:
    case ActionKind::kCaptureClose:
      return "registration captures run in the console or `telear capture`";
    case ActionKind::kScreenshot:
    case ActionKind::kQuit:
      return "the console's automation only";
    default:
      return {};
  }
}

// The plan's identity for the summary cache: its waypoints as they stand.
std::string plan_key(const session::Plan& plan) {
  std::ostringstream key;
  key.precision(17);
  for (const session::PlanWaypoint& w : plan.waypoints()) {
    for (Eigen::Index i = 0; i < w.q.size(); ++i) key << w.q[i] << ',';
    key << '|' << w.min_duration << '|' << (w.gripper ? *w.gripper : -1.0) << '|' << w.label << ';';
  }
  return key.str();
}

}  // namespace

BrowserOperator::BrowserOperator(std::shared_ptr<const OperatorSetup> setup,
                                 std::shared_ptr<OperatorOutbox> outbox)
    : setup_(std::move(setup)), outbox_(std::move(outbox)) {
  thread_ = std::thread([this] { run(); });
}

BrowserOperator::~BrowserOperator() {
  stop();
  if (thread_.joinable()) thread_.join();
}

void BrowserOperator::receive(std::string text) {
  {
    std::lock_guard lock(mutex_);
    inbox_.push_back(std::move(text));
  }
  wake_.notify_one();
}

void BrowserOperator::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
}

void BrowserOperator::run() {
  outbox_->send_text(hello_message(*setup_->model, setup_->embedded));
  outbox_->send_text(connection_message("disconnected"));
  connection_ = "disconnected";
  auto last_update = std::chrono::steady_clock::now();
  auto next_state = last_update;
  for (;;) {
    std::deque<std::string> messages;
    {
      std::unique_lock lock(mutex_);
      wake_.wait_for(lock, std::chrono::duration<double>(kUpdatePeriodS),
                     [this] { return stopping_ || !inbox_.empty(); });
      if (stopping_) break;
      messages.swap(inbox_);
    }
    for (const std::string& text : messages) handle(text);
    if (!session_) continue;
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last_update).count();
    if (dt >= kUpdatePeriodS || !messages.empty()) {
      session_->update(std::max(dt, 1e-3));
      last_update = now;
    }
    const std::string state =
        session_->robot_connected() && session_->vision_connected() ? "connected" : "connecting";
    if (state != connection_) {
      outbox_->send_text(connection_message(state));
      connection_ = state;
    }
    if (now >= next_state) {
      send_state();
      next_state = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                             std::chrono::duration<double>(kStatePeriodS));
    }
  }
  if (session_) session_->disconnect();  // releases the lease before the socket's end
  session_.reset();
}

void BrowserOperator::handle(const std::string& text) {
  const json message = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!message.is_object() || !message.contains("type") || !message["type"].is_string()) {
    outbox_->send_text(
        result_message(-1, false, "not a message: a JSON object with a \"type\" is expected"));
    return;
  }
  const std::string type = message["type"].get<std::string>();
  std::int64_t id = -1;
  if (const auto it = message.find("id"); it != message.end() && it->is_number_integer()) {
    id = it->get<std::int64_t>();
  }
  if (type == "connect") {
    const json token = message.value("token", json());
    connect(token.is_string() ? token.get<std::string>() : std::string());
  } else if (type == "command") {
    const json line = message.value("line", json());
    if (!line.is_string()) {
      outbox_->send_text(result_message(id, false, "command: \"line\" must be a string"));
      return;
    }
    command(id, line.get<std::string>());
  } else if (type == "ping") {
    const json page_ms = message.value("page_ms", json(0.0));
    outbox_->send_text(pong_message(id, page_ms.is_number() ? page_ms.get<double>() : 0.0,
                                    static_cast<double>(core::monotonic_ns()) / 1e6));
  } else if (type == "shown") {
    // The page's own capture -> shown, from its clock-offset estimate (docs/web.md).
    const json latency = message.value("latency_ms", json());
    if (latency.is_number() && std::isfinite(latency.get<double>())) {
      const double now = static_cast<double>(core::monotonic_ns()) / 1e9;
      shown_.emplace_back(now, latency.get<double>());
      while (!shown_.empty() && shown_.front().first < now - kShownWindowS) shown_.pop_front();
    }
  } else {
    outbox_->send_text(result_message(id, false, "unknown message type '" + type + "'"));
  }
}

void BrowserOperator::connect(const std::string& token) {
  if (session_) {
    session_->disconnect();
    session_.reset();
  }
  outbox_->send_text(connection_message("connecting"));
  connection_ = "connecting";
  auto refuse = [this](const std::string& reason) {
    outbox_->send_text(connection_message("refused", reason));
    connection_ = "refused";
  };
  if (token.empty()) return refuse("no token: type the servers' token");
  session::SessionOptions options = setup_->session_options;
  options.robot.token = token;
  options.vision.token = token;
  options.robot.client_name = "telear-web";
  options.vision.client_name = "telear-web";
  // The video goes to the page as the server sent it, from the receive thread; the socket's
  // queue keeps only the newest frame not yet sent.
  std::weak_ptr<OperatorOutbox> outbox = outbox_;
  options.vision.on_received = [outbox](const net::ReceivedStereoFrame& frame) {
    if (auto o = outbox.lock()) {
      o->send_binary(video_frame_message(frame, core::monotonic_ns()),
                     OperatorOutbox::Kind::kVideo);
    }
  };
  // The shared cameras (their look-up tables are megabytes: not copied per tab), or the vision
  // server's, asked with this tab's token.
  std::vector<EyeProjection> asked;
  if (!setup_->eyes) {
    net::VisionClient probe(options.vision);
    auto info = probe.get_camera_info();
    if (!info) return refuse(refusal_reason(info.error().message));
    if (!info->found)
      return refuse(
          "the vision server has no calibration; start telear web "
          "with --calibration");
    const vision::StereoCameraModel cameras{
        vision::resized_camera(info->cameras.left, setup_->width, setup_->height),
        vision::resized_camera(info->cameras.right, setup_->width, setup_->height)};
    options.cameras = cameras;  // the session's registration check draws with them too
    asked = {eye_projection("left", cameras.left), eye_projection("right", cameras.right)};
  }
  const std::vector<EyeProjection>& eyes = setup_->eyes ? *setup_->eyes : asked;
  auto created = session::Session::create(setup_->model, options);
  if (!created) return refuse(created.error().message);
  // The robot server is the authority on the token: a refused GetInfo ends the attempt before
  // a stream is opened or anything of the arm is sent.
  auto info = (*created)->robot().get_info();
  if (!info) return refuse(refusal_reason(info.error().message));
  session_ = std::move(*created);
  session_->connect();
  ui_ = console::UiState{};
  ui_.embedded = setup_->embedded;
  last_event_time_ = -1.0;
  ghost_pose_.emplace(*setup_->model, setup_->body);
  real_pose_.emplace(*setup_->model, setup_->body);
  plan_key_ = "-";
  outbox_->send_text(setup_->model_json);
  outbox_->send_text(cameras_message(eyes));
  for (std::size_t i = 0; i < eyes.size(); ++i) {
    outbox_->send_binary(lut_message(static_cast<int>(i), eyes[i]));
  }
}

void BrowserOperator::command(std::int64_t id, const std::string& line) {
  if (!session_) {
    outbox_->send_text(result_message(id, false, "not connected: connect with the token first"));
    return;
  }
  if (line.find_first_of("\r\n") != std::string::npos) {
    outbox_->send_text(result_message(id, false, "one action per command line"));
    return;
  }
  auto parsed = console::parse_ui_script(line, setup_->model->dof(), "command");
  if (!parsed) {
    outbox_->send_text(result_message(id, false, parsed.error().message));
    return;
  }
  if (parsed->size() != 1 || !std::holds_alternative<console::UiAction>(parsed->front().step)) {
    outbox_->send_text(result_message(
        id, false,
        parsed->empty() ? "empty command line" : "'" + line + "': waits are the scripts' only"));
    return;
  }
  const auto& action = std::get<console::UiAction>(parsed->front().step);
  if (const std::string why = not_in_the_page(action.kind); !why.empty()) {
    outbox_->send_text(result_message(
        id, false, std::string(console::to_string(action.kind)) + ": not in the page: " + why));
    return;
  }
  Status status = action.kind == console::ActionKind::kEStop
                      ? session_->estop("e-stop from the browser operator")
                      : console::apply_action(*session_, ui_, action);
  if (action.kind == console::ActionKind::kEStop) {
    ui_.last_message = status ? "E-STOP sent" : "e-stop: " + status.error().message;
    ui_.last_failed = !status;
  }
  // The state first, then the answer: when the page reads the answer, its state already shows
  // the action's effect.
  session_->update(1e-3);
  send_state();
  outbox_->send_text(result_message(id, static_cast<bool>(status),
                                    status ? ui_.last_message : status.error().message));
}

void BrowserOperator::send_state() {
  outbox_->send_text(state_json(), OperatorOutbox::Kind::kState);
}

std::string BrowserOperator::state_json() {
  const session::Session& s = *session_;
  const session::SessionView& view = s.view();
  const session::SessionStats stats = s.stats();
  const core::ArmBody& body = setup_->body;

  std::vector<double> ghost;
  ghost_pose_->set_configuration(view.ghost_q);
  ghost_pose_->set_gripper_opening(body.gripper_opening_m(view.ghost_gripper));
  for (const Eigen::Matrix4f& m : ghost_pose_->T_base_part()) append_matrix(ghost, m);
  json real = nullptr;
  json real_q = nullptr;
  std::string mode = "unknown";
  bool estop = false;
  if (view.real) {
    std::vector<double> matrices;
    real_pose_->set_configuration(view.real->state.q);
    real_pose_->set_gripper_opening(body.gripper_opening_m(view.real->state.gripper));
    for (const Eigen::Matrix4f& m : real_pose_->T_base_part()) append_matrix(matrices, m);
    real = matrices;
    real_q = degrees(view.real->state.q);
    mode = core::to_string(view.real->state.mode);
    estop = view.real->state.estop;
  }
  json contact = json::array();
  for (int part = 0; part < body.part_count(); ++part) {
    const int link = body.parts[static_cast<std::size_t>(part)].link;
    if (std::find(view.ghost_contact_frames.begin(), view.ghost_contact_frames.end(), link) !=
        view.ghost_contact_frames.end()) {
      contact.push_back(part);
    }
  }
  json latency = json::object();
  for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) {
    latency[net::kLatencyStages[i].key] = stats.latency[i].p50_s * 1e3;
  }
  std::vector<double> shown;
  for (const auto& [time, ms] : shown_) shown.push_back(ms);
  const net::LatencySummary shown_summary = net::summarize_latency(shown);  // any unit: ms here

  const session::Plan& plan = s.plan();
  if (const std::string key = plan_key(plan); key != plan_key_) {
    plan_key_ = key;
    auto trajectory = plan.trajectory();
    plan_duration_s_ = trajectory ? trajectory->duration() : 0.0;
    auto hash = s.plan_hash();
    plan_hash_ = hash ? *hash : std::string();
  }
  json waypoints = json::array();
  for (const session::PlanWaypoint& w : plan.waypoints()) {
    json waypoint{{"label", w.label}, {"duration_s", w.min_duration}, {"q_deg", degrees(w.q)}};
    if (w.gripper) waypoint["gripper"] = *w.gripper;
    waypoints.push_back(std::move(waypoint));
  }
  json events = json::array();
  for (const session::SessionEvent& e : s.events()) {
    if (e.time <= last_event_time_) continue;
    events.push_back({{"t", e.time},
                      {"kind", e.kind == session::SessionEvent::Kind::kInfo      ? "info"
                               : e.kind == session::SessionEvent::Kind::kWarning ? "warning"
                                                                                 : "error"},
                      {"message", e.message}});
    last_event_time_ = e.time;
  }
  json message{
      {"type", "state"},
      {"t", s.now()},
      {"robot_connected", s.robot_connected()},
      {"vision_connected", s.vision_connected()},
      {"in_control", s.in_control()},
      {"mode", mode},
      {"estop", estop},
      {"display", view.display.mode == session::DisplayMode::kAR ? "ar" : "vr"},
      {"display_reason", view.display.reason},
      {"fps", stats.video_fps},
      {"frame_age_ms", stats.frame_age_s * 1e3},
      {"video_bytes_per_s", stats.video_bytes_per_s},
      {"state_age_ms", stats.robot_state_age_s * 1e3},
      {"latency_ms", latency},
      {"shown_ms",
       {{"p50", shown_summary.p50_s}, {"p99", shown_summary.p99_s}, {"samples", shown.size()}}},
      {"ghost", ghost},
      {"real", real},
      {"contact_parts", contact},
      {"ghost_q_deg", degrees(view.ghost_q)},
      {"real_q_deg", real_q},
      {"gripper", view.ghost_gripper},
      {"plan",
       {{"waypoints", waypoints},
        {"duration_s", plan_duration_s_},
        {"hash", plan_hash_},
        {"previewed_hash", s.previewed_hash()},
        {"executed_hash", s.executed_hash()},
        {"previewing", view.previewing},
        {"executing", s.executing()},
        {"last_result", s.last_execution_result()}}},
      {"view",
       {{"style", ui_.wireframe ? "wire" : "solid"},
        {"opacity", ui_.ghost_opacity},
        {"show_reported", ui_.show_reported},
        {"undistorted", ui_.undistorted}}},
      {"message", ui_.last_message},
      {"message_failed", ui_.last_failed},
      {"events", events}};
  return message.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace telear::web
