#include "telear/net/robot_service.hpp"

#include "telear/core/number_format.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <utility>

#include "telear/core/clock.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/net/robot_messages.hpp"

#include "steady_time.hpp"

namespace telear::net {

namespace {

constexpr double kMaxStateRateHz = 250.0;
constexpr double kDefaultStateRateHz = 50.0;

const char* code_name(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::OK:
      return "OK";
    case grpc::StatusCode::UNAUTHENTICATED:
      return "UNAUTHENTICATED";
    case grpc::StatusCode::PERMISSION_DENIED:
      return "PERMISSION_DENIED";
    case grpc::StatusCode::INVALID_ARGUMENT:
      return "INVALID_ARGUMENT";
    case grpc::StatusCode::FAILED_PRECONDITION:
      return "FAILED_PRECONDITION";
    case grpc::StatusCode::UNAVAILABLE:
      return "UNAVAILABLE";
    default:
      return "ERROR";
  }
}

// Untrusted text for messages and the log: non-printable bytes become '?' and long text is
// cut (the validation's message gives the real length).
std::string printable(const std::string& text, size_t shown = 64) {
  std::string out = text.substr(0, shown);
  for (char& c : out) {
    if (c < 0x20 || c > 0x7e) c = '?';
  }
  return text.size() > shown ? out + "..." : out;
}

std::string quoted(const std::string& id) {
  // Appended rather than "'" + printable(id) + "'", which trips GCC 12's -Wrestrict false
  // positive (GCC PR 105329) once the function is inlined into enough callers.
  std::string out = "'";
  out += printable(id);
  out += '\'';
  return out;
}

grpc::Status invalid(const Error& error) {
  return {grpc::StatusCode::INVALID_ARGUMENT, error.message};
}

// An execution's acceptance into ExecuteTrajectory's or ExecutePlan's response (the same four
// fields in both).
template <typename Response, typename Execution>
void fill_execution(Response& response, const Execution& e) {
  response.set_duplicate(e.duplicate);
  response.set_status(to_proto(e.status));
  response.set_duration_s(e.duration_s);
  response.set_accepted_ns(e.accepted_ns);
}

}  // namespace

RobotService::RobotService(core::RobotDriver& driver, BearerAuth auth, LeaseOptions lease_options,
                           CommandLimits limits, std::unique_ptr<MotionCollisionGuard> guard)
    : driver_(driver),
      auth_(std::move(auth)),
      limits_(limits),
      guard_(std::move(guard)),
      lease_(lease_options, [this](const LeaseLapse& lapse) { on_lease_lapse(lapse); }) {}

RobotService::~RobotService() {
  begin_shutdown();
}

void RobotService::begin_shutdown() {
  {
    std::lock_guard lock(shutdown_mutex_);
    shutting_down_ = true;
  }
  shutdown_cv_.notify_all();
  lease_.stop();
}

void RobotService::on_lease_lapse(const LeaseLapse& lapse) {
  const std::string reason = "the lease of '" + lapse.holder +
                             "' lapsed: not renewed within its heartbeat period (dead-man)";
  driver_.stop(reason);
  spdlog::warn("robot lease of '{}' lapsed; controlled stop began {:.2f} ms after the expiry",
               lapse.holder, static_cast<double>(lapse.stop_started_ns - lapse.expired_ns) * 1e-6);
}

grpc::Status RobotService::finish(grpc::ServerContext* context, const std::string& what,
                                  grpc::Status status) {
  const std::string who = describe_caller(*context);
  if (status.ok()) {
    spdlog::info("robot command from {}: {}: accepted", who, what);
  } else {
    spdlog::warn("robot command from {}: {}: rejected ({}): {}", who, what,
                 code_name(status.error_code()), status.error_message());
  }
  return status;
}

grpc::Status RobotService::admit(grpc::ServerContext* context, const std::string& what,
                                 const std::string& lease_id) {
  if (grpc::Status s = auth_.authorize_command(*context); !s.ok()) return finish(context, what, s);
  if (auto holder = lease_.check(lease_id); !holder) {
    return finish(context, what,
                  {grpc::StatusCode::PERMISSION_DENIED, what + ": " + holder.error().message});
  }
  return grpc::Status::OK;
}

grpc::StatusCode RobotService::driver_rejection_code() const {
  const core::RobotState state = driver_.snapshot().state;
  const bool busy = state.estop || !state.trajectory_id.empty();
  return busy ? grpc::StatusCode::FAILED_PRECONDITION : grpc::StatusCode::INVALID_ARGUMENT;
}

// [SECTION] State

grpc::Status RobotService::GetInfo(grpc::ServerContext* context, const v1::GetInfoRequest*,
                                   v1::RobotInfo* response) {
  if (grpc::Status s = auth_.authorize_read(*context); !s.ok()) return s;
  fill_model_info(*driver_.model(), *response);
  response->set_urdf(driver_.urdf());
  response->set_tip_link(driver_.tip_link());
  response->set_driver(driver_.name());
  response->set_heartbeat_period_ns(lease_.options().default_heartbeat_ns);
  response->set_start_tolerance(driver_.start_tolerance());
  response->set_max_waypoints(limits_.max_waypoints);
  response->set_server_time_ns(core::monotonic_ns());
  if (guard_) {
    response->set_workspace_yaml(guard_->workspace_yaml());
    response->set_safety_margin_m(guard_->safety_margin_m());
    response->set_collision_checked(true);
  }
  return grpc::Status::OK;
}

grpc::Status RobotService::StreamState(grpc::ServerContext* context,
                                       const v1::StreamStateRequest* request,
                                       grpc::ServerWriter<v1::RobotState>* writer) {
  if (grpc::Status s = auth_.authorize_read(*context); !s.ok()) return s;
  double rate = request->rate_hz();
  if (rate == 0.0) rate = kDefaultStateRateHz;
  if (!(rate >= 1.0 && rate <= kMaxStateRateHz)) {
    return {grpc::StatusCode::INVALID_ARGUMENT, "state rate " + core::format_number(rate, "%g") +
                                                    " Hz is outside 1..250 Hz (0: 50 Hz)"};
  }
  const auto period_ns = static_cast<std::int64_t>(1e9 / rate);
  std::int64_t next_ns = core::monotonic_ns();
  std::uint64_t sequence = 0;
  v1::RobotState message;
  while (true) {
    {
      std::unique_lock lock(shutdown_mutex_);
      shutdown_cv_.wait_until(lock, steady_time(next_ns), [&] { return shutting_down_; });
      if (shutting_down_) {
        return {grpc::StatusCode::UNAVAILABLE, "the robot server is shutting down"};
      }
    }
    if (context->IsCancelled()) return grpc::Status::CANCELLED;
    const core::DriverSnapshot snapshot = driver_.snapshot();
    message.Clear();
    fill_state(snapshot.state, message);
    message.set_sequence(++sequence);
    message.set_capture_ns(snapshot.capture_ns);
    message.set_lease_holder(lease_.holder());
    {
      std::lock_guard lock(ghost_mutex_);
      if (!ghost_.lease_id.empty() && lease_.check(ghost_.lease_id)) {
        message.mutable_ghost_q()->Assign(ghost_.q.data(), ghost_.q.data() + ghost_.q.size());
        message.set_ghost_gripper(ghost_.gripper);
        message.set_ghost_ns(ghost_.received_ns);
      }
    }
    std::string last_id;
    {
      std::lock_guard lock(last_mutex_);
      last_id = last_trajectory_id_;
    }
    if (!last_id.empty()) {
      if (auto record = driver_.trajectory_record(last_id);
          record && record->status != core::TrajectoryStatus::kRunning) {
        message.set_last_trajectory_id(record->id);
        message.set_last_trajectory_status(to_proto(record->status));
        message.set_last_trajectory_message(record->message);
      }
    }
    message.set_server_send_ns(core::monotonic_ns());
    if (!writer->Write(message)) return grpc::Status::OK;  // the client went away
    // Keep the rate; after a stall (a slow client) skip the missed ticks, never burst.
    next_ns = std::max(next_ns + period_ns, core::monotonic_ns());
  }
}

grpc::Status RobotService::Ping(grpc::ServerContext* context, const v1::PingRequest* request,
                                v1::PingResponse* response) {
  const std::int64_t received_ns = core::monotonic_ns();
  if (grpc::Status s = auth_.authorize_read(*context); !s.ok()) return s;
  response->set_client_send_ns(request->client_send_ns());
  response->set_server_receive_ns(received_ns);
  response->set_server_send_ns(core::monotonic_ns());
  return grpc::Status::OK;
}

// [SECTION] Lease

grpc::Status RobotService::AcquireLease(grpc::ServerContext* context,
                                        const v1::AcquireLeaseRequest* request,
                                        v1::Lease* response) {
  std::string holder = printable(request->client_name());
  if (holder.empty()) holder = "unnamed client";
  const std::string what = "acquire lease as '" + holder + "'";
  if (grpc::Status s = auth_.authorize_command(*context); !s.ok()) return finish(context, what, s);
  if (request->heartbeat_period_ns() < 0) {
    return finish(context, what,
                  {grpc::StatusCode::INVALID_ARGUMENT,
                   "acquire lease: the heartbeat period is negative (0: the server's default)"});
  }
  auto grant = lease_.acquire(holder, request->heartbeat_period_ns());
  if (!grant) {
    return finish(context, what,
                  {grpc::StatusCode::PERMISSION_DENIED, "acquire lease: " + grant.error().message});
  }
  response->set_lease_id(grant->lease_id);
  response->set_holder(grant->holder);
  response->set_heartbeat_period_ns(grant->heartbeat_ns);
  response->set_expires_ns(grant->expires_ns);
  return finish(
      context,
      what + " (heartbeat " +
          core::format_number(static_cast<double>(grant->heartbeat_ns) * 1e-6, "%.0f ms") + ")",
      grpc::Status::OK);
}

grpc::Status RobotService::RenewLease(grpc::ServerContext* context,
                                      const v1::RenewLeaseRequest* request, v1::Lease* response) {
  // Renewals are not logged when they succeed: several per second would drown the log.
  if (grpc::Status s = auth_.authorize_command(*context); !s.ok()) {
    return finish(context, "renew lease", s);
  }
  std::optional<Eigen::VectorXd> ghost;
  if (request->ghost_q_size() > 0) {
    const Eigen::VectorXd q =
        Eigen::Map<const Eigen::VectorXd>(request->ghost_q().data(), request->ghost_q_size());
    if (Status s = check_ghost(*driver_.model(), q, request->ghost_gripper()); !s) {
      return finish(context, "renew lease", invalid(Error{"renew lease: " + s.error().message}));
    }
    ghost = q;
  }
  auto grant = lease_.renew(request->lease_id());
  if (!grant) {
    return finish(context, "renew lease",
                  {grpc::StatusCode::PERMISSION_DENIED, "renew lease: " + grant.error().message});
  }
  response->set_lease_id(grant->lease_id);
  response->set_holder(grant->holder);
  response->set_heartbeat_period_ns(grant->heartbeat_ns);
  response->set_expires_ns(grant->expires_ns);
  if (ghost) {
    driver_.show_ghost(*ghost, request->ghost_gripper());
    std::lock_guard lock(ghost_mutex_);
    ghost_ = {request->lease_id(), *ghost, request->ghost_gripper(), core::monotonic_ns()};
  }
  return grpc::Status::OK;
}

grpc::Status RobotService::ReleaseLease(grpc::ServerContext* context,
                                        const v1::ReleaseLeaseRequest* request,
                                        v1::ReleaseLeaseResponse*) {
  const std::string what = "release lease";
  if (grpc::Status s = auth_.authorize_command(*context); !s.ok()) return finish(context, what, s);
  auto holder = lease_.release(request->lease_id());
  if (!holder) {
    return finish(
        context, what,
        {grpc::StatusCode::PERMISSION_DENIED, "release lease: " + holder.error().message});
  }
  // Nobody is in charge any more: any motion stops, as on a lapse.
  driver_.stop("the lease was released by '" + holder.value() + "'");
  return finish(context, what, grpc::Status::OK);
}

// [SECTION] Motion

grpc::Status RobotService::Jog(grpc::ServerContext* context, const v1::JogRequest* request,
                               v1::JogResponse* response) {
  const std::int64_t arrived_ns = core::monotonic_ns();
  std::string what = "jog";
  if (grpc::Status s = admit(context, what, request->lease_id()); !s.ok()) return s;
  auto jog = jog_command_from_request(*driver_.model(), *request);
  if (!jog) return finish(context, what, invalid(jog.error()));
  what += " (" + jog->description + ")";
  if (Status s = check_jog_expiry(request->expires_ns(), arrived_ns, limits_); !s) {
    return finish(context, what, invalid(s.error()));
  }
  if (jog->motion && guard_) {
    // The target is resolved here, checked with its path, and handed to the driver as a joint
    // target, so the arm goes exactly where the check said it may.
    const core::RobotState state = driver_.snapshot().state;
    const core::MotionOutcome planned = core::apply_motion(*driver_.model(), state.q, *jog->motion);
    if (!planned.accepted) return finish(context, what, invalid(Error{planned.rejection.message}));
    if (Status s = guard_->check_jog(*driver_.model(), state.q, planned.q, state.gripper); !s) {
      return finish(context, what, invalid(s.error()));
    }
    auto outcome = driver_.jog(core::JointTarget{planned.q}, request->expires_ns());
    if (!outcome) {
      return finish(context, what, {driver_rejection_code(), outcome.error().message});
    }
    const Eigen::VectorXd& q = outcome->q;
    response->mutable_target_q()->Assign(q.data(), q.data() + q.size());
    if (planned.singularity) response->set_singularity_warning(planned.singularity->message);
    response->set_ik_config(planned.ik_config);
  } else if (jog->motion) {
    auto outcome = driver_.jog(*jog->motion, request->expires_ns());
    if (!outcome) {
      return finish(context, what, {driver_rejection_code(), outcome.error().message});
    }
    const Eigen::VectorXd& q = outcome->q;
    response->mutable_target_q()->Assign(q.data(), q.data() + q.size());
    if (outcome->singularity) response->set_singularity_warning(outcome->singularity->message);
    response->set_ik_config(outcome->ik_config);
  } else {
    if (guard_) {
      // The arm moves at this velocity until the jog expires (or a joint reaches its limit):
      // check the line to where it would be then.
      const core::RobotState state = driver_.snapshot().state;
      const double horizon_s =
          static_cast<double>(std::max<std::int64_t>(request->expires_ns() - arrived_ns, 0)) * 1e-9;
      const core::RobotModel& model = *driver_.model();
      const Eigen::VectorXd q_end = (state.q + jog->velocity * horizon_s)
                                        .cwiseMax(model.lower_limits())
                                        .cwiseMin(model.upper_limits());
      if (Status s = guard_->check_jog(*driver_.model(), state.q, q_end, state.gripper); !s) {
        return finish(context, what, invalid(s.error()));
      }
    }
    if (Status s = driver_.jog_velocity(jog->velocity, request->expires_ns()); !s) {
      return finish(context, what, {driver_rejection_code(), s.error().message});
    }
  }
  return finish(context, what, grpc::Status::OK);
}

std::optional<RobotService::Execution> RobotService::first_acceptance(const std::string& id) const {
  const auto first = accepted_.find(id);
  if (first == accepted_.end()) return std::nullopt;
  const auto record = driver_.trajectory_record(id);
  return Execution{true, record ? record->status : core::TrajectoryStatus::kRunning,
                   first->second.duration_s, first->second.accepted_ns};
}

grpc::Status RobotService::check_motion(const std::string& id,
                                        const core::TimedWaypoints& waypoints,
                                        const core::Trajectory* timed) const {
  const core::RobotState state = driver_.snapshot().state;
  if (state.estop) {
    return {grpc::StatusCode::FAILED_PRECONDITION, "trajectory " + quoted(id) +
                                                       " rejected: the e-stop is engaged (" +
                                                       state.estop_reason + "); reset it first"};
  }
  if (state.mode != core::RobotMode::kIdle) {
    const std::string busy = state.trajectory_id.empty()
                                 ? std::string("the arm is ") + to_string(state.mode)
                                 : "trajectory " + quoted(state.trajectory_id) + " is running";
    return {grpc::StatusCode::FAILED_PRECONDITION,
            "trajectory " + quoted(id) + " rejected: " + busy +
                "; wait until the arm is at rest (or cancel)"};
  }
  if (Status s = check_start_state(*driver_.model(), id, waypoints.q.front(), state.q,
                                   driver_.start_tolerance());
      !s) {
    return invalid(s.error());
  }
  if (guard_) {
    Status s = timed ? guard_->check_trajectory(*timed, state.gripper)
                     : guard_->check_samples(*driver_.model(), waypoints, state.gripper);
    if (!s) return invalid(Error{"trajectory " + quoted(id) + " rejected: " + s.error().message});
  }
  return grpc::Status::OK;
}

grpc::Status RobotService::start(const std::string& id, const core::TimedWaypoints& waypoints,
                                 const core::Trajectory* timed, Execution& execution) {
  if (grpc::Status s = check_motion(id, waypoints, timed); !s.ok()) return s;
  auto accepted = driver_.execute(id, waypoints);
  if (!accepted) return {driver_rejection_code(), accepted.error().message};
  accepted_[id] = FirstAcceptance{accepted->accepted_ns, accepted->record.duration};
  {
    std::lock_guard last_lock(last_mutex_);
    last_trajectory_id_ = id;
  }
  execution = Execution{accepted->duplicate, accepted->record.status, accepted->record.duration,
                        accepted->accepted_ns};
  return grpc::Status::OK;
}

grpc::Status RobotService::ExecuteTrajectory(grpc::ServerContext* context,
                                             const v1::ExecuteTrajectoryRequest* request,
                                             v1::ExecuteTrajectoryResponse* response) {
  const std::string& id = request->trajectory_id();
  std::string what = "execute trajectory " + quoted(id) + " (" +
                     std::to_string(request->waypoints_size()) + " waypoints)";
  if (grpc::Status s = admit(context, what, request->lease_id()); !s.ok()) return s;
  if (Status s = check_trajectory_id(id, limits_); !s) {
    return finish(context, what, invalid(s.error()));
  }
  std::lock_guard lock(execute_mutex_);
  response->set_trajectory_id(id);
  if (const auto first = first_acceptance(id)) {
    fill_execution(*response, *first);
    return finish(context, what + ": a duplicate of the first acceptance, not executed again",
                  grpc::Status::OK);
  }
  auto waypoints = timed_waypoints_from_request(*driver_.model(), *request, limits_);
  if (!waypoints) return finish(context, what, invalid(waypoints.error()));
  Execution execution;
  if (grpc::Status s = start(id, *waypoints, nullptr, execution); !s.ok())
    return finish(context, what, s);
  fill_execution(*response, execution);
  return finish(context, what + ", " + core::format_number(execution.duration_s, "%.3f s"),
                grpc::Status::OK);
}

grpc::Status RobotService::prepare_plan(const v1::PlanMessage& plan, PlanHashCheck check,
                                        std::optional<PreparedPlan>& prepared) const {
  // Validated and timed with the client's algorithm, hash compared: nothing moves before.
  auto received = plan_from_message(*driver_.model(), plan, limits_, check);
  if (!received) return invalid(received.error());
  // The arm follows the trajectory's samples, every waypoint on one (Trajectory::sampled).
  auto samples = received->trajectory.sampled(kPlanExecutionRateHz);
  if (!samples) {
    return invalid(
        Error{"plan " + quoted(plan.plan_id()) + " rejected: " + samples.error().message});
  }
  if (grpc::Status s = check_motion(plan.plan_id(), *samples, &received->trajectory); !s.ok()) {
    return s;
  }
  prepared.emplace(PreparedPlan{std::move(*received), std::move(*samples)});
  return grpc::Status::OK;
}

grpc::Status RobotService::ExecutePlan(grpc::ServerContext* context,
                                       const v1::ExecutePlanRequest* request,
                                       v1::ExecutePlanResponse* response) {
  const v1::PlanMessage& plan = request->plan();
  const std::string& id = plan.plan_id();
  std::string what = "execute plan " + quoted(id) + " (" + std::to_string(plan.waypoints_size()) +
                     " waypoints, " + printable(plan.algorithm()) + ")";
  if (grpc::Status s = admit(context, what, request->lease_id()); !s.ok()) return s;
  if (Status s = check_plan_id(id, limits_); !s) return finish(context, what, invalid(s.error()));
  std::lock_guard lock(execute_mutex_);
  response->set_plan_id(id);
  response->set_algorithm(std::string(core::kTrajectoryAlgorithm));
  if (const auto first = first_acceptance(id)) {
    fill_execution(*response, *first);
    if (const auto hash = accepted_plan_hashes_.find(id); hash != accepted_plan_hashes_.end()) {
      response->set_plan_hash(*plan_hash_bytes(hash->second));
    }
    return finish(context, what + ": a duplicate of the first acceptance, not executed again",
                  grpc::Status::OK);
  }
  std::optional<PreparedPlan> prepared;
  if (grpc::Status s = prepare_plan(plan, PlanHashCheck::kCompare, prepared); !s.ok()) {
    return finish(context, what, s);
  }
  Execution execution;
  if (grpc::Status s = start(id, prepared->samples, &prepared->plan.trajectory, execution); !s.ok())
    return finish(context, what, s);
  const std::string& hash = prepared->plan.hash;
  accepted_plan_hashes_[id] = hash;
  fill_execution(*response, execution);
  response->set_plan_hash(*plan_hash_bytes(hash));
  return finish(context,
                what + ", " + core::format_number(execution.duration_s, "%.3f s") + ", hash " +
                    hash.substr(0, 12),
                grpc::Status::OK);
}

grpc::Status RobotService::PreviewPlan(grpc::ServerContext* context,
                                       const v1::PreviewPlanRequest* request,
                                       v1::PreviewPlanResponse* response) {
  const v1::PlanMessage& plan = request->plan();
  const std::string& id = plan.plan_id();
  const std::string what = "preview plan " + quoted(id) + " (" +
                           std::to_string(plan.waypoints_size()) + " waypoints, " +
                           (plan.algorithm().empty() ? std::string("the server's algorithm")
                                                     : printable(plan.algorithm())) +
                           ")";
  // Read-only: whoever may read the state may ask what a plan would do (no lease).
  if (grpc::Status s = auth_.authorize_read(*context); !s.ok()) return finish(context, what, s);
  if (Status s = check_plan_id(id, limits_); !s) return finish(context, what, invalid(s.error()));
  // Under the execution lock, so the answer reflects the arm as ExecutePlan would see it.
  std::lock_guard lock(execute_mutex_);
  if (accepted_.count(id) != 0) {
    // ExecutePlan would answer this id with its first acceptance and run nothing new.
    return finish(context, what,
                  invalid(Error{"plan " + quoted(id) +
                                " rejected: its id was already accepted, so ExecutePlan would "
                                "answer with that first acceptance and not run this plan; "
                                "choose a new id"}));
  }
  // No algorithm named: the server's. A client that leaves the timing to the server need
  // not know its name; the answer gives it, for ExecutePlan, which requires it.
  v1::PlanMessage named;
  if (plan.algorithm().empty()) {
    named = plan;
    named.set_algorithm(std::string(core::kTrajectoryAlgorithm));
  }
  std::optional<PreparedPlan> prepared;
  if (grpc::Status s =
          prepare_plan(plan.algorithm().empty() ? named : plan, PlanHashCheck::kIgnore, prepared);
      !s.ok()) {
    return finish(context, what, s);
  }
  const core::Trajectory& trajectory = prepared->plan.trajectory;
  driver_.show_preview(id, prepared->samples);
  response->set_plan_id(id);
  response->set_plan_hash(*plan_hash_bytes(prepared->plan.hash));
  response->set_algorithm(std::string(core::kTrajectoryAlgorithm));
  response->set_duration_s(trajectory.duration());
  const core::TimedWaypoints& samples = prepared->samples;
  if (request->with_samples()) {
    response->set_sample_rate_hz(kPlanExecutionRateHz);
    if (samples.q.size() > static_cast<std::size_t>(kMaxPreviewSamples)) {
      response->set_samples_omitted(true);
    } else {
      // In ExecuteTrajectory's wire form (times rounded to whole nanoseconds): what a client
      // would draw, and could send back as a sampled trajectory.
      v1::ExecuteTrajectoryRequest sampled;
      fill_trajectory_request(id, samples, sampled);
      response->mutable_samples()->Swap(sampled.mutable_waypoints());
      response->mutable_gripper()->Swap(sampled.mutable_gripper());
    }
  }
  return finish(context,
                what + ": " + core::format_number(trajectory.duration(), "%.3f s") + ", hash " +
                    prepared->plan.hash.substr(0, 12),
                grpc::Status::OK);
}

grpc::Status RobotService::Cancel(grpc::ServerContext* context, const v1::CancelRequest* request,
                                  v1::CancelResponse*) {
  const std::string reason = request->reason().empty() ? "cancelled" : request->reason();
  const std::string what = "cancel (" + reason + ")";
  if (grpc::Status s = admit(context, what, request->lease_id()); !s.ok()) return s;
  driver_.stop(reason);
  return finish(context, what, grpc::Status::OK);
}

grpc::Status RobotService::SetGripper(grpc::ServerContext* context,
                                      const v1::SetGripperRequest* request,
                                      v1::SetGripperResponse*) {
  const std::string what = "set gripper to " + core::format_number(request->opening(), "%.3f");
  if (grpc::Status s = admit(context, what, request->lease_id()); !s.ok()) return s;
  if (Status s = check_gripper_opening(request->opening()); !s) {
    return finish(context, what, invalid(s.error()));
  }
  if (Status s = driver_.set_gripper(request->opening()); !s) {
    return finish(context, what, {driver_rejection_code(), s.error().message});
  }
  return finish(context, what, grpc::Status::OK);
}

grpc::Status RobotService::EStop(grpc::ServerContext* context, const v1::EStopRequest* request,
                                 v1::EStopResponse*) {
  const std::string reason =
      request->reason().empty() ? "e-stop from " + describe_caller(*context) : request->reason();
  const std::string what = "e-stop (" + reason + ")";
  // Anyone authenticated may stop the arm, lease or not.
  if (grpc::Status s = auth_.authorize_command(*context); !s.ok()) return finish(context, what, s);
  driver_.estop(reason);
  return finish(context, what, grpc::Status::OK);
}

grpc::Status RobotService::ResetEStop(grpc::ServerContext* context,
                                      const v1::ResetEStopRequest* request,
                                      v1::ResetEStopResponse*) {
  const std::string what = "reset e-stop";
  if (grpc::Status s = admit(context, what, request->lease_id()); !s.ok()) return s;
  if (Status s = driver_.reset_estop(); !s) {
    return finish(context, what, {grpc::StatusCode::FAILED_PRECONDITION, s.error().message});
  }
  return finish(context, what, grpc::Status::OK);
}

}  // namespace telear::net
