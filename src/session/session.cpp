#include "telear/session/session.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <sstream>

#include "telear/core/clock.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/geometry/carried_objects.hpp"
#include "telear/session/capture_session.hpp"

namespace telear::session {

namespace {

// A frame captured after the newest report (the states late, or a slower state stream): the
// newest report stands for the arm up to this long after it (2 periods at the stream's 100 Hz
// plus slack); beyond, the arm at capture is not known and not drawn.
constexpr double kCaptureArmTolerance_s = 0.05;

cv::Mat as_mat(const core::Image& image) {
  return cv::Mat(image.height, image.width, CV_8UC(image.channels),
                 const_cast<std::uint8_t*>(image.pixels.data()));
}

// An eye for marker detection: the RGB image, or the luma plane of a frame decoded to planes
// (the grey image detection converts RGB to anyway: no conversion at all).
cv::Mat detection_view(const core::Image& rgb, const core::YCbCrImage& planes) {
  if (!rgb.empty() || planes.empty()) return as_mat(rgb);
  return cv::Mat(planes.height, planes.width, CV_8UC1, const_cast<std::uint8_t*>(planes.y.data()));
}

}  // namespace

Session::Session(core::RobotModelPtr model, SessionOptions options)
    : model_(std::move(model)),
      options_(std::move(options)),
      ghost_(model_),
      plan_(model_),
      display_(options_.display),
      predictor_(options_.prediction),
      epoch_ns_(core::monotonic_ns()) {}

Session::~Session() {
  disconnect();
}

Result<std::unique_ptr<Session>> Session::create(core::RobotModelPtr model,
                                                 SessionOptions options) {
  if (!model) return Error{"session: no robot model"};
  if (!(std::isfinite(options.sample_rate_hz) && options.sample_rate_hz > 0.0)) {
    return Error{"session: sample_rate_hz must be a positive number"};
  }
  if (!(std::isfinite(options.injected_video_delay_s) && options.injected_video_delay_s >= 0.0)) {
    return Error{"session: injected_video_delay_s must be >= 0"};
  }
  if (!(std::isfinite(options.injected_state_delay_s) && options.injected_state_delay_s >= 0.0)) {
    return Error{"session: injected_state_delay_s must be >= 0"};
  }
  if (Status s = options.prediction.validate(); !s) return Error{"session: " + s.error().message};
  if (!(std::isfinite(options.prediction_min_delay_s) && options.prediction_min_delay_s >= 0.0)) {
    return Error{"session: prediction_min_delay_s must be a finite number >= 0"};
  }
  if (Status s = options.display.validate(); !s.ok()) {
    return Error{"session: display options: " + s.error().message};
  }
  if (!(options.monitor.tolerance > 0.0)) {
    return Error{"session: the execution monitor's tolerance must be > 0"};
  }
  if (!(std::isfinite(options.safety_margin_m) && options.safety_margin_m >= 0.0)) {
    return Error{"session: safety_margin_m must be a finite number >= 0"};
  }
  if (Status s = options.plan_check.validate(); !s) {
    return Error{"session: plan_check: " + s.error().message};
  }
  std::unique_ptr<geometry::CollisionChecker> checker;
  if (options.description && options.workspace) {
    // The graspable objects are the task's targets, not obstacles: the fingers touch the box
    // at the grasp on purpose. Validation checks a carried one (ValidationOptions::workspace).
    geometry::CollisionSetupOptions setup;
    setup.mesh_collision = options.mesh_collision;
    auto made = geometry::make_collision_checker(
        *options.description, geometry::static_obstacles(*options.workspace), setup);
    if (!made) return Error{"session: collision checker: " + made.error().message};
    checker = std::make_unique<geometry::CollisionChecker>(std::move(*made));
  }
  std::unique_ptr<Session> session(new Session(std::move(model), std::move(options)));
  if (checker) {
    session->checker_ = std::move(checker);
    session->clearance_.emplace(*session->checker_, session->options_.safety_margin_m);
    session->update_clearance(session->ghost_.q(), session->ghost_.gripper());
  }
  session->robot_ = std::make_unique<net::RobotClient>(session->options_.robot);
  session->vision_ = std::make_unique<net::VisionClient>(session->options_.vision);
  if (session->options_.cameras && session->options_.marker) {
    session->registration_.emplace(session->model_, *session->options_.cameras,
                                   *session->options_.marker);
  }
  return session;
}

double Session::now() const {
  return core::ns_to_s(core::monotonic_ns() - epoch_ns_);
}

void Session::log(SessionEvent::Kind kind, std::string message, WorkflowStep step,
                  std::string plan_id, std::string plan_hash) {
  events_.push_back(
      {now(), kind, std::move(message), step, std::move(plan_id), std::move(plan_hash)});
  if (options_.on_event) options_.on_event(events_.back(), core::monotonic_ns());
  while (events_.size() > options_.max_events) events_.pop_front();
}

// [SECTION] connection

void Session::connect() {
  if (connected_) return;
  robot_->start();
  vision_->start();
  connected_ = true;
  log(SessionEvent::Kind::kInfo, "connecting to the robot server at " + options_.robot.address +
                                     " and the vision server at " + options_.vision.address);
}

void Session::disconnect() {
  if (!connected_) return;
  close_capture();  // it uses the robot client: a pose being added is cancelled first
  if (robot_->lease_held()) (void)robot_->release_lease();
  robot_->stop();
  vision_->stop();
  connected_ = false;
  log(SessionEvent::Kind::kInfo, "disconnected");
}

// [SECTION] registration capture

Status Session::open_capture(CaptureSessionOptions options) {
  if (!connected_) return Error{"registration capture: not connected"};
  if (!in_control()) {
    return Error{
        "registration capture: take control first (the lease: nobody else moves the "
        "arm between the poses)"};
  }
  close_capture();
  net::VisionClientOptions vision = options_.vision;
  vision.width = 0;  // the source's size: what the calibration describes
  vision.height = 0;
  vision.jpeg_quality = 100;
  vision.max_rate_hz = 0.0;
  vision.client_name += "-capture";
  auto client = std::make_unique<net::VisionClient>(vision);
  client->start();
  const std::string directory = options.directory;
  auto opened = CaptureSession::open(*model_, *robot_, *client, std::move(options));
  if (!opened) return opened.error();
  capture_vision_ = std::move(client);
  capture_ = std::move(*opened);
  log(SessionEvent::Kind::kInfo, "registration capture into " + directory);
  return Status::Ok();
}

void Session::close_capture() {
  if (!capture_) return;
  log(SessionEvent::Kind::kInfo, "registration capture closed (" +
                                     std::to_string(capture_->poses().size()) + " poses in " +
                                     capture_->directory() + ")");
  capture_.reset();
  capture_vision_.reset();
}

bool Session::robot_connected() const {
  return robot_ && robot_->connected();
}
bool Session::vision_connected() const {
  return vision_ && vision_->connected();
}
bool Session::in_control() const {
  return robot_ && robot_->lease_held();
}

Status Session::take_control() {
  if (!start_tolerance_) {
    if (auto info = robot_->get_info()) start_tolerance_ = info->start_tolerance;
  }
  Status s = robot_->acquire_lease(options_.lease_heartbeat_s);
  if (!s.ok()) {
    log(SessionEvent::Kind::kError, s.error().message);
    return s;
  }
  log(SessionEvent::Kind::kInfo, "lease acquired: this console commands the robot",
      WorkflowStep::kLeaseAcquired);
  return s;
}

Status Session::release_control() {
  Status s = robot_->release_lease();
  log(s.ok() ? SessionEvent::Kind::kInfo : SessionEvent::Kind::kError,
      s.ok() ? "lease released" : s.error().message,
      s.ok() ? WorkflowStep::kLeaseReleased : WorkflowStep::kNone);
  return s;
}

Status Session::estop(const std::string& reason) {
  Status s = robot_->estop(reason);
  log(s.ok() ? SessionEvent::Kind::kWarning : SessionEvent::Kind::kError,
      s.ok() ? "E-STOP: " + reason : "e-stop failed: " + s.error().message, WorkflowStep::kEStop);
  if (s.ok() && executing_) {
    executing_ = false;
    last_result_ = "aborted: " + reason;
  }
  return s;
}

Status Session::reset_estop() {
  Status s = robot_->reset_estop();
  log(s.ok() ? SessionEvent::Kind::kInfo : SessionEvent::Kind::kError,
      s.ok() ? "e-stop reset" : s.error().message,
      s.ok() ? WorkflowStep::kEStopReset : WorkflowStep::kNone);
  return s;
}

// [SECTION] ghost

core::MotionOutcome Session::move_ghost(const core::MotionCommand& command) {
  core::MotionOutcome outcome = ghost_.apply(command);
  if (!outcome.accepted) {
    log(SessionEvent::Kind::kWarning, "ghost: " + outcome.rejection.message);
  } else if (outcome.singularity) {
    log(SessionEvent::Kind::kWarning, "ghost: " + outcome.singularity->message);
  }
  if (outcome.accepted && !preview_ && !executing_) update_clearance(ghost_.q(), ghost_.gripper());
  return outcome;
}

const ClearanceState& Session::ghost_clearance() const {
  static const ClearanceState unchecked;
  return clearance_ ? clearance_->state() : unchecked;
}

void Session::update_clearance(const Eigen::VectorXd& q, double gripper) {
  if (!clearance_ || q.size() != model_->dof()) return;
  view_.ghost_contact_frames = clearance_->update(q, gripper).contact_frames;
}

std::optional<net::RobotStateSample> Session::reported_state() const {
  return options_.injected_state_delay_s > 0.0 ? delivered_state_ : robot_->latest_state();
}

std::optional<Eigen::VectorXd> Session::real_q() const {
  const auto state = reported_state();
  if (!state || state->state.q.size() != model_->dof()) return std::nullopt;
  return state->state.q;
}

Status Session::ghost_to_real() {
  const auto state = reported_state();
  if (!state) return Error{"ghost = real: no state from the robot server yet"};
  Status s = ghost_.reset_to(state->state.q, state->state.gripper);
  if (!s.ok()) log(SessionEvent::Kind::kError, "ghost = real: " + s.error().message);
  if (s.ok() && !preview_ && !executing_) update_clearance(ghost_.q(), ghost_.gripper());
  return s;
}

// [SECTION] real robot

Result<net::JogAck> Session::jog_real(const core::MotionCommand& command) {
  auto ack = robot_->jog(command, options_.jog_validity_s);
  if (!ack) log(SessionEvent::Kind::kWarning, ack.error().message);
  return ack;
}

Status Session::set_real_gripper(double opening) {
  Status s = robot_->set_gripper(opening);
  if (!s.ok()) log(SessionEvent::Kind::kWarning, s.error().message);
  return s;
}

Result<net::TrajectoryAck> Session::initialize_real(const Eigen::VectorXd& q) {
  const auto current = real_q();
  if (!current) return Error{"initialize: no state from the robot server yet"};
  Plan move(model_);
  if (Status s = move.add(PlanWaypoint(*current, 0.0, std::nullopt, "current")); !s.ok())
    return s.error();
  if (Status s = move.add(PlanWaypoint(q, 0.0, std::nullopt, "target")); !s.ok()) {
    return Error{"initialize: " + s.error().message};
  }
  auto samples = move.timed_waypoints(options_.sample_rate_hz);
  if (!samples) return Error{"initialize: " + samples.error().message};
  const std::string id = "init-" + std::to_string(epoch_ns_) + "-" + std::to_string(++executions_);
  auto ack = robot_->execute(id, *samples);
  log(ack ? SessionEvent::Kind::kInfo : SessionEvent::Kind::kError,
      ack ? "initializing the real robot (" + id + ")" : ack.error().message);
  return ack;
}

// [SECTION] plan

Status Session::add_ghost_waypoint(double min_duration, std::string label) {
  Status s = plan_.add_from(ghost_, min_duration, std::move(label));
  if (!s.ok()) log(SessionEvent::Kind::kWarning, "plan: " + s.error().message);
  return s;
}

Status Session::start_preview(PreviewOptions options) {
  auto trajectory = plan_.trajectory();
  if (!trajectory) return Error{"preview: " + trajectory.error().message};
  auto hash = core::plan_hash(*trajectory);
  if (!hash) return Error{"preview: " + hash.error().message};
  previewed_hash_ = *hash;
  preview_.emplace(std::move(*trajectory), options);
  preview_->play();
  log(SessionEvent::Kind::kInfo, "preview started (hash " + previewed_hash_.substr(0, 12) + ")",
      WorkflowStep::kPreview, {}, previewed_hash_);
  return Status::Ok();
}

void Session::stop_preview() {
  if (!preview_) return;
  preview_.reset();
  log(SessionEvent::Kind::kInfo, "preview stopped", WorkflowStep::kPreview, {}, previewed_hash_);
}

ValidationReport Session::validate_plan() {
  ValidationReport report = check_plan();
  auto hash = plan_hash();
  const std::string h = hash ? *hash : std::string();
  log(report.ok() ? SessionEvent::Kind::kInfo : SessionEvent::Kind::kWarning,
      "validate: " + report.summary(), WorkflowStep::kValidate, {}, h);
  if (report.collision && !report.collision->collision_free()) {
    const geometry::PlanCollision& first = report.collision->collisions.front();
    log(SessionEvent::Kind::kWarning,
        "collision: " + first.body + " - " + first.other + " at " +
            core::format_number(first.time_s, "%.2f") + " s, " +
            core::format_number(first.depth_m * 1000.0, "%.1f") + " mm deep",
        WorkflowStep::kCollision, {}, h);
  }
  return report;
}

ValidationReport Session::check_plan() const {
  ValidationOptions options;
  if (start_tolerance_) options.start_tolerance = *start_tolerance_;
  options.sample_rate_hz = options_.sample_rate_hz;
  options.collision_checker = checker_.get();
  if (checker_) options.workspace = &*options_.workspace;  // the carried box is checked too
  options.safety_margin_m = options_.safety_margin_m;
  options.collision_check = options_.plan_check;
  return session::validate_plan(plan_, real_q(), options);
}

Result<std::string> Session::plan_hash() const {
  auto trajectory = plan_.trajectory();
  if (!trajectory) return trajectory.error();
  return core::plan_hash(*trajectory);
}

Result<net::PlanAck> Session::execute_plan() {
  if (executing_) return Error{"execute: a plan is already executing (" + executing_id_ + ")"};
  if (!in_control()) return Error{"execute: take control (the lease) first"};
  const ValidationReport report = check_plan();
  if (!report.ok()) {
    log(SessionEvent::Kind::kError, "execute: the plan is not valid: " + report.summary(),
        WorkflowStep::kExecute);
    return Error{"execute: the plan is not valid: " + report.summary()};
  }
  auto trajectory = plan_.trajectory();
  if (!trajectory) return Error{"execute: " + trajectory.error().message};
  const std::string id = "plan-" + std::to_string(epoch_ns_) + "-" + std::to_string(++executions_);
  const double sent_s = now();
  auto ack = robot_->execute_plan(id, *trajectory);
  if (!ack) {
    log(SessionEvent::Kind::kError, ack.error().message, WorkflowStep::kExecute, id);
    return ack;
  }
  executed_hash_ = ack->plan_hash;
  stop_preview();
  // The robot took the plan up between the request and its answer: the middle of the two.
  predictor_.follow(*trajectory, id, 0.5 * (sent_s + now()));
  monitor_.emplace(model_, std::move(*trajectory), 0.0, options_.monitor);
  executing_id_ = id;
  executing_ = true;
  last_result_.clear();
  log(SessionEvent::Kind::kInfo,
      "executing " + id + " (" + std::to_string(plan_.size()) + " waypoints, " +
          core::format_number(ack->duration_s, "%.2f") + " s, hash " +
          ack->plan_hash.substr(0, 12) +
          (ack->plan_hash == previewed_hash_ ? ", as previewed)" : ", not the last preview)"),
      WorkflowStep::kExecute, id, ack->plan_hash);
  return ack;
}

Status Session::cancel_execution(const std::string& reason) {
  Status s = robot_->cancel(reason);
  if (s.ok() && executing_) {
    executing_ = false;
    last_result_ = "cancelled: " + reason;
  }
  log(s.ok() ? SessionEvent::Kind::kWarning : SessionEvent::Kind::kError,
      s.ok() ? "cancelled: " + reason : s.error().message, WorkflowStep::kExecute, executing_id_,
      executed_hash_);
  return s;
}

// [SECTION] per frame

void Session::update(double dt) {
  const double t = now();
  deliver_states(t);
  view_.real = delivered_state_;
  double capture_s = 0.0;
  if (view_.real) {
    const auto& real = *view_.real;
    capture_s = core::ns_to_s(real.capture_client_ns() - epoch_ns_);
    view_.real_state_age_s = std::max(0.0, t - capture_s);
    state_history_.add(capture_s, real.state.q, real.state.gripper);
    if (!ghost_synced_ && real.state.q.size() == model_->dof()) {
      ghost_synced_ = ghost_.reset_to(real.state.q, real.state.gripper).ok();
    }
  }

  update_monitor();
  if (!executing_) predictor_.stop();
  view_.prediction = predictor_.predict(t, {view_.real ? &view_.real->state : nullptr, capture_s});
  view_.executing = executing_;
  view_.previewing = preview_.has_value() && !executing_;
  if (executing_ && monitor_ && view_.real) {
    // The commanded pose: the plan where the robot is now (its trajectory time plus the age
    // of the report).
    const auto& real = view_.real->state;
    const double plan_time =
        real.trajectory_id == executing_id_ ? real.trajectory_time + view_.real_state_age_s : 0.0;
    Eigen::VectorXd q;
    monitor_->trajectory().sample(plan_time, q);
    view_.ghost_q = q;
    view_.ghost_gripper = monitor_->trajectory().gripper_at(plan_time).value_or(real.gripper);
  } else if (view_.previewing) {
    const PreviewFrame frame = preview_->advance(dt);
    view_.ghost_q = frame.q;
    view_.ghost_gripper = frame.gripper.value_or(ghost_.gripper());
  } else {
    view_.ghost_q = ghost_.q();
    view_.ghost_gripper = ghost_.gripper();
  }
  update_clearance(view_.ghost_q, view_.ghost_gripper);
  // The rehearsed ghost rides on the lease's heartbeat, for drivers that show it to the arm's
  // own tools (RViz through the ROS driver); only changes are sent.
  if (ghost_synced_ && robot_->lease_held()) robot_->set_ghost(ghost_.q(), ghost_.gripper());

  update_frame(t);
  view_.capture_arm.reset();
  if (view_.frame) {
    // The simulated rig names the robot state it drew (up to a state period before its
    // capture); a camera's picture is of the capture instant.
    const std::int64_t shown_ns = view_.frame->scene_state_ns != 0 ? view_.frame->scene_state_ns
                                                                   : view_.frame->capture_ns_left;
    view_.capture_arm =
        state_history_.at(core::ns_to_s(shown_ns - epoch_ns_), kCaptureArmTolerance_s);
  }
  // Drawn once the state is old enough for the prediction to differ from it to the eye, and
  // always while it keeps a late video in AR (the arm now, over the video of then).
  view_.show_prediction =
      view_.prediction.available &&
      (view_.prediction.horizon_s >= options_.prediction_min_delay_s || view_.display.predicted);
  update_registration(t);
  update_capture();
  live_series_.update(t, view_.real ? &*view_.real : nullptr, t - view_.real_state_age_s,
                      recent_frames_.empty() ? nullptr : recent_frames_.back().second.get(),
                      view_.display);
}

void Session::deliver_states(double t) {
  auto latest = robot_->latest_state();
  state_taken_ns_ = core::monotonic_ns();
  if (latest && latest->sequence != state_sequence_) {
    state_sequence_ = latest->sequence;
    held_states_.push_back(std::move(*latest));
  }
  // The newest state old enough to be "delivered" (all of them without a delay).
  const std::int64_t now_ns = epoch_ns_ + core::s_to_ns(t);
  const std::int64_t delay_ns = core::s_to_ns(options_.injected_state_delay_s);
  while (!held_states_.empty() &&
         (delay_ns == 0 || held_states_.front().receive_ns + delay_ns <= now_ns)) {
    delivered_state_ = std::move(held_states_.front());
    held_states_.pop_front();
  }
  while (held_states_.size() > 1024) held_states_.pop_front();  // a delay longer than the buffer
}

void Session::update_capture() {
  if (!capture_) return;
  auto added = capture_->poll_add();
  if (!added) return;
  if (*added) {
    log(SessionEvent::Kind::kInfo, "registration: " + (*added)->summary());
  } else {
    log(SessionEvent::Kind::kWarning, "registration: " + added->error().message);
  }
}

void Session::update_frame(double t) {
  // Newly decoded frames (latest-wins: only the newest one since the last update).
  if (auto taken = vision_->wait_frame(frame_number_, 0.0)) {
    frame_number_ = taken->second;
    delayed_.emplace_back(taken->second, taken->first);
    recent_frames_.emplace_back(t, taken->first);
    while (!recent_frames_.empty() && recent_frames_.front().first < t - 2.0) {
      recent_frames_.pop_front();
    }
  }
  // The newest frame that has been "delivered" (held back by the injected delay, if any).
  const std::int64_t now_ns = epoch_ns_ + core::s_to_ns(t);
  const std::int64_t delay_ns = core::s_to_ns(options_.injected_video_delay_s);
  while (!delayed_.empty() && delayed_.front().second->decoded_ns + delay_ns <= now_ns) {
    view_.frame = delayed_.front().second;
    delayed_.pop_front();
  }
  while (delayed_.size() > 512) delayed_.pop_front();  // a delay longer than the buffer

  std::optional<double> capture;
  if (view_.frame) capture = core::ns_to_s(view_.frame->capture_ns_left - epoch_ns_);
  const DisplayMode before = display_.mode();
  view_.display = display_.update(t, capture, view_.prediction.available);
  if (display_.mode() != before) {
    // The message starts with the new mode: a recording's AR/VR timeline reads it.
    log(SessionEvent::Kind::kInfo,
        std::string(display_.mode() == DisplayMode::kAR ? "ar" : "vr") + ": display " +
            to_string(before) + " -> " + to_string(display_.mode()) + " (" + view_.display.reason +
            ")",
        WorkflowStep::kDisplayMode);
  }
}

void Session::update_monitor() {
  if (!executing_ || !monitor_ || !view_.real) return;
  const auto& sample = *view_.real;
  const auto& real = sample.state;
  if (real.trajectory_id == executing_id_) {
    const TrackingStatus& status =
        monitor_->update_at_plan_time(real.trajectory_time, real.q, real.q_commanded);
    if (status.cancel) {
      (void)robot_->cancel(status.cancel_message);
      executing_ = false;
      last_result_ = "cancelled: " + status.cancel_message;
      log(SessionEvent::Kind::kError, "execution monitor: " + status.cancel_message,
          WorkflowStep::kFault, executing_id_, executed_hash_);
    }
    return;
  }
  if (sample.last_trajectory_id == executing_id_ &&
      sample.last_trajectory_status != core::TrajectoryStatus::kRunning) {
    monitor_->update_at_plan_time(monitor_->trajectory().duration(), real.q);
    executing_ = false;
    last_result_ = to_string(sample.last_trajectory_status);
    if (!sample.last_trajectory_message.empty()) {
      last_result_ += ": " + sample.last_trajectory_message;
    }
    log(sample.last_trajectory_status == core::TrajectoryStatus::kCompleted
            ? SessionEvent::Kind::kInfo
            : SessionEvent::Kind::kWarning,
        executing_id_ + " " + last_result_, WorkflowStep::kExecute, executing_id_, executed_hash_);
  }
}

void Session::update_registration(double t) {
  if (!registration_ || !view_.frame || t < next_registration_check_) return;
  next_registration_check_ = t + options_.registration_check_period_s;
  const net::DecodedStereoFrame& frame = *view_.frame;
  Eigen::VectorXd q;
  if (frame.scene_q.size() == model_->dof()) {
    q = frame.scene_q;
  } else {
    const auto nearest = state_history_.nearest(core::ns_to_s(frame.capture_ns_left - epoch_ns_));
    if (!nearest || nearest->q.size() != model_->dof()) return;
    q = nearest->q;
  }
  if (!q.allFinite()) return;
  residual_ = registration_->check(detection_view(frame.left, frame.left_planes),
                                   detection_view(frame.right, frame.right_planes), q);
  residual_.arm_moving = state_history_.moving_near(
      core::ns_to_s(frame.capture_ns_left - epoch_ns_), q, StereoResidual::kMotionWindowS,
      StereoResidual::kMotionToleranceRad);
  ++residual_checks_;
}

void Session::note_shown(std::uint64_t frame_id, const std::optional<vision::FrameCode>& code,
                         std::int64_t shown_ns) {
  if (frame_id == shown_frame_id_) return;
  shown_frame_id_ = frame_id;
  std::optional<double> shown_s;
  if (code && code->frame == static_cast<std::uint32_t>(frame_id)) {
    std::int64_t capture_ns = code->capture_ns;  // server clock
    if (auto offset = vision_->clock_offset()) capture_ns -= offset->offset_ns;
    shown_s = core::ns_to_s(shown_ns - capture_ns);
  }
  const double t = now();
  recent_shown_.emplace_back(t, shown_s);
  while (!recent_shown_.empty() && recent_shown_.front().first < t - 2.0) {
    recent_shown_.pop_front();
  }
}

SessionStats Session::stats() const {
  SessionStats stats;
  if (recent_frames_.size() >= 2) {
    const double span = recent_frames_.back().first - recent_frames_.front().first;
    if (span > 0) {
      stats.video_fps = static_cast<double>(recent_frames_.size() - 1) / span;
      double bytes = 0;
      for (std::size_t i = 1; i < recent_frames_.size(); ++i) {
        bytes += static_cast<double>(recent_frames_[i].second->message_bytes);
      }
      stats.video_bytes_per_s = bytes / span;
    }
  }
  net::LatencySeries latency;
  for (const auto& [time, frame] : recent_frames_) latency.add(frame->latency);
  stats.latency = latency.summarize();
  stats.robot_state_age_s = view_.real_state_age_s;
  stats.command_bytes_sent = robot_->command_bytes_sent();
  if (auto offset = robot_->clock_offset())
    stats.robot_round_trip_s = core::ns_to_s(offset->delay_ns);
  stats.residual = residual_;
  stats.residual_checks = residual_checks_;
  stats.frame_age_s = view_.display.frame_age.value_or(0.0);
  std::vector<double> shown;
  const double window_start = now() - 2.0;  // a stopped video leaves no figure behind
  for (const auto& [time, seconds] : recent_shown_) {
    if (time < window_start) continue;
    if (seconds) {
      shown.push_back(*seconds);
    } else {
      ++stats.shown_without_code;
    }
  }
  stats.shown = net::summarize_latency(shown);
  return stats;
}

}  // namespace telear::session
