#include "telear/net/robot_client.hpp"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

#include "telear/core/clock.hpp"
#include "telear/net/client_base.hpp"
#include "telear/net/latest_slot.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/net/robot_messages.hpp"
#include "telear/v1/robot.grpc.pb.h"

namespace telear::net {

namespace {

using Stub = v1::RobotService::Stub;

std::chrono::nanoseconds seconds(double s) {
  return std::chrono::nanoseconds(core::s_to_ns(s));
}

RobotInfo info_from_proto(const v1::RobotInfo& message) {
  RobotInfo info;
  info.model_name = message.model_name();
  info.urdf = message.urdf();
  info.tip_link = message.tip_link();
  info.collision_checked = message.collision_checked();
  info.workspace_yaml = message.workspace_yaml();
  info.safety_margin_m = message.safety_margin_m();
  for (const v1::JointInfo& j : message.joints()) {
    info.joints.push_back(JointInfo{j.name(), j.prismatic(), j.min_position(), j.max_position(),
                                    j.max_velocity(), j.max_acceleration()});
  }
  for (const v1::NamedConfiguration& c : message.named_configurations()) {
    info.named_configurations.emplace_back(
        c.name(), Eigen::Map<const Eigen::VectorXd>(c.q().data(), c.q_size()));
  }
  info.driver = message.driver();
  info.heartbeat_period_s = core::ns_to_s(message.heartbeat_period_ns());
  info.start_tolerance = message.start_tolerance();
  info.max_waypoints = message.max_waypoints();
  return info;
}

}  // namespace

std::int64_t RobotStateSample::capture_client_ns() const {
  return capture_ns - clock_offset_ns;
}

struct RobotClient::Impl {
  explicit Impl(RobotClientOptions o)
      : options(std::move(o)),
        base(options, "robot server"),
        stub(v1::RobotService::NewStub(base.channel())) {}

  RobotClientOptions options;
  ClientBase base;  // channel, metadata, reconnect back-off and accounting
  std::unique_ptr<Stub> stub;
  LatestSlot<RobotStateSample> states;

  mutable std::mutex mutex;  // everything below but the atomics
  ClockOffsetEstimator estimator;
  std::condition_variable wake;  // release and destruction wake the heartbeat
  std::thread stream_thread, ping_thread;

  std::string lease_id;
  bool lease_held = false;
  bool heartbeat_stop = false;
  std::string lease_error;
  std::int64_t heartbeat_ns = 0;
  Eigen::VectorXd ghost_q;  // the latest set_ghost
  double ghost_gripper = 0.0;
  std::uint64_t ghost_version = 0;  // counts changes; 0: no ghost yet
  std::uint64_t ghost_sent = 0;     // the version a renewal the server accepted carried
  std::thread heartbeat_thread;

  std::atomic<std::uint64_t> command_bytes{0};

  Error error(const std::string& command, const grpc::Status& status) const {
    return base.error(command, status);
  }

  template <typename Request, typename Response>
  grpc::Status call(grpc::Status (Stub::*method)(grpc::ClientContext*, const Request&, Response*),
                    const Request& request, Response* response, bool is_command) {
    grpc::ClientContext context;
    base.prepare(context);
    if (is_command) command_bytes += request.ByteSizeLong();
    return (stub.get()->*method)(&context, request, response);
  }

  std::string current_lease_id() const {
    std::lock_guard lock(mutex);
    return lease_id;
  }

  std::int64_t to_server_ns(std::int64_t client_ns) const {
    std::lock_guard lock(mutex);
    return estimator.to_server_ns(client_ns);
  }

  void stream_loop();
  void ping_loop();
  void heartbeat_loop();
  Result<double> ping();
};

void RobotClient::Impl::stream_loop() {
  v1::StreamStateRequest request;
  request.set_rate_hz(options.state_rate_hz);
  base.run_stream([&](grpc::ClientContext& context, const std::function<void()>& on_message) {
    auto reader = stub->StreamState(&context, request);
    v1::RobotState message;
    while (reader->Read(&message)) {
      const std::int64_t received = core::monotonic_ns();
      on_message();
      RobotStateSample sample;
      sample.state = state_from_proto(message);
      sample.sequence = states.count() + 1;
      sample.capture_ns = message.capture_ns();
      sample.server_send_ns = message.server_send_ns();
      sample.receive_ns = received;
      sample.lease_holder = message.lease_holder();
      sample.last_trajectory_id = message.last_trajectory_id();
      sample.last_trajectory_status = from_proto(message.last_trajectory_status());
      sample.last_trajectory_message = message.last_trajectory_message();
      if (message.ghost_q_size() > 0) {
        sample.ghost_q =
            Eigen::Map<const Eigen::VectorXd>(message.ghost_q().data(), message.ghost_q_size());
        sample.ghost_gripper = message.ghost_gripper();
        sample.ghost_ns = message.ghost_ns();
      }
      {
        std::lock_guard lock(mutex);
        sample.clock_offset_ns = estimator.to_server_ns(0);
      }
      if (options.on_state) options.on_state(sample);
      states.put(std::move(sample));
    }
    return reader->Finish();
  });
}

Result<double> RobotClient::Impl::ping() {
  v1::PingRequest request;
  v1::PingResponse response;
  request.set_client_send_ns(core::monotonic_ns());
  const grpc::Status status = call(&Stub::Ping, request, &response, false);
  const std::int64_t received = core::monotonic_ns();
  if (!status.ok()) return error("ping", status);
  PingSample sample{response.client_send_ns(), response.server_receive_ns(),
                    response.server_send_ns(), received};
  {
    std::lock_guard lock(mutex);
    estimator.add(sample);
  }
  return core::ns_to_s(received - request.client_send_ns());
}

void RobotClient::Impl::ping_loop() {
  do {
    (void)ping();
  } while (base.sleep_while_running(options.ping_period_s));
}

void RobotClient::Impl::heartbeat_loop() {
  std::int64_t last_renewal = core::monotonic_ns();
  while (true) {
    std::string id;
    std::int64_t period;
    {
      std::unique_lock lock(mutex);
      period = heartbeat_ns;
      wake.wait_for(lock, std::chrono::nanoseconds(period / 3), [&] { return heartbeat_stop; });
      if (heartbeat_stop) return;
      id = lease_id;
    }
    v1::RenewLeaseRequest request;
    request.set_lease_id(id);
    std::uint64_t ghost = 0;
    {
      std::lock_guard lock(mutex);
      if (ghost_version != ghost_sent) {
        ghost = ghost_version;
        request.mutable_ghost_q()->Assign(ghost_q.data(), ghost_q.data() + ghost_q.size());
        request.set_ghost_gripper(ghost_gripper);
      }
    }
    v1::Lease response;
    // Renewals are not counted as command bytes: both ways of moving the arm renew alike.
    const grpc::Status status = call(&Stub::RenewLease, request, &response, false);
    const std::int64_t now = core::monotonic_ns();
    if (status.ok()) {
      last_renewal = now;
      if (ghost != 0) {
        std::lock_guard lock(mutex);
        ghost_sent = std::max(ghost_sent, ghost);
      }
      continue;
    }
    const bool refused = status.error_code() == grpc::StatusCode::PERMISSION_DENIED ||
                         status.error_code() == grpc::StatusCode::UNAUTHENTICATED;
    if (refused || now - last_renewal >= period) {
      std::lock_guard lock(mutex);
      lease_held = false;
      lease_error = "lease lost: " + error("renew lease", status).message;
      return;
    }
  }
}

// [SECTION] RobotClient

RobotClient::RobotClient(RobotClientOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {}

RobotClient::~RobotClient() {
  if (lease_held()) (void)release_lease();
  stop();
  std::thread heartbeat;
  {
    std::lock_guard lock(impl_->mutex);
    impl_->heartbeat_stop = true;
    heartbeat = std::move(impl_->heartbeat_thread);
  }
  impl_->wake.notify_all();
  if (heartbeat.joinable()) heartbeat.join();
}

const RobotClientOptions& RobotClient::options() const {
  return impl_->options;
}

void RobotClient::start() {
  if (!impl_->base.begin()) return;
  std::lock_guard lock(impl_->mutex);
  impl_->stream_thread = std::thread([this] { impl_->stream_loop(); });
  impl_->ping_thread = std::thread([this] { impl_->ping_loop(); });
}

void RobotClient::stop() {
  impl_->base.stop();
  std::thread stream, ping;
  {
    std::lock_guard lock(impl_->mutex);
    stream = std::move(impl_->stream_thread);
    ping = std::move(impl_->ping_thread);
  }
  if (stream.joinable()) stream.join();
  if (ping.joinable()) ping.join();
}

bool RobotClient::connected() const {
  return impl_->base.connected();
}

ReconnectStats RobotClient::reconnect_stats() const {
  return impl_->base.reconnect_stats();
}

Result<RobotInfo> RobotClient::get_info() {
  v1::RobotInfo response;
  const grpc::Status status = impl_->call(&Stub::GetInfo, v1::GetInfoRequest(), &response, false);
  if (!status.ok()) return impl_->error("get info", status);
  return info_from_proto(response);
}

std::optional<RobotStateSample> RobotClient::latest_state() const {
  auto taken = impl_->states.try_take();
  if (!taken) return std::nullopt;
  return *taken->item;
}

std::optional<RobotStateSample> RobotClient::wait_state(std::uint64_t after_sequence,
                                                        double timeout_s) const {
  auto taken = impl_->states.wait_take(after_sequence, seconds(timeout_s));
  if (!taken) return std::nullopt;
  return *taken->item;
}

std::optional<ClockOffset> RobotClient::clock_offset() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->estimator.estimate();
}

Result<double> RobotClient::ping() {
  return impl_->ping();
}

Status RobotClient::acquire_lease(double heartbeat_period_s) {
  if (lease_held()) return Status::Ok();
  v1::AcquireLeaseRequest request;
  request.set_client_name(impl_->options.client_name);
  request.set_heartbeat_period_ns(core::s_to_ns(heartbeat_period_s));
  v1::Lease response;
  const grpc::Status status = impl_->call(&Stub::AcquireLease, request, &response, true);
  if (!status.ok()) return impl_->error("acquire lease", status);
  std::thread previous;
  {
    std::lock_guard lock(impl_->mutex);
    impl_->lease_id = response.lease_id();
    impl_->heartbeat_ns = response.heartbeat_period_ns();
    impl_->lease_held = true;
    impl_->lease_error.clear();
    impl_->heartbeat_stop = false;
    impl_->ghost_sent = 0;  // a new lease: the server has not seen this client's ghost
    previous = std::move(impl_->heartbeat_thread);  // a lost lease's thread has returned
  }
  if (previous.joinable()) previous.join();
  std::lock_guard lock(impl_->mutex);
  impl_->heartbeat_thread = std::thread([this] { impl_->heartbeat_loop(); });
  return Status::Ok();
}

Status RobotClient::release_lease() {
  std::thread heartbeat;
  std::string id;
  {
    std::lock_guard lock(impl_->mutex);
    impl_->heartbeat_stop = true;
    heartbeat = std::move(impl_->heartbeat_thread);
    id = impl_->lease_id;
  }
  impl_->wake.notify_all();
  if (heartbeat.joinable()) heartbeat.join();
  if (id.empty()) return Status::Ok();
  v1::ReleaseLeaseRequest request;
  request.set_lease_id(id);
  v1::ReleaseLeaseResponse response;
  const grpc::Status status = impl_->call(&Stub::ReleaseLease, request, &response, true);
  {
    std::lock_guard lock(impl_->mutex);
    impl_->lease_held = false;
    impl_->lease_id.clear();
  }
  if (!status.ok()) return impl_->error("release lease", status);
  return Status::Ok();
}

bool RobotClient::lease_held() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->lease_held;
}

std::string RobotClient::lease_error() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->lease_error;
}

namespace {

JogAck jog_ack(const v1::JogResponse& response) {
  JogAck ack;
  ack.target_q =
      Eigen::Map<const Eigen::VectorXd>(response.target_q().data(), response.target_q_size());
  ack.singularity_warning = response.singularity_warning();
  ack.ik_config = response.ik_config();
  return ack;
}

}  // namespace

Result<JogAck> RobotClient::jog(const core::MotionCommand& command, double valid_for_s) {
  v1::JogRequest request;
  request.set_lease_id(impl_->current_lease_id());
  request.set_expires_ns(impl_->to_server_ns(core::monotonic_ns() + core::s_to_ns(valid_for_s)));
  fill_jog_request(command, request);
  v1::JogResponse response;
  const grpc::Status status = impl_->call(&Stub::Jog, request, &response, true);
  if (!status.ok()) return impl_->error("jog", status);
  return jog_ack(response);
}

Result<JogAck> RobotClient::jog_velocity(const Eigen::VectorXd& qd, double valid_for_s) {
  v1::JogRequest request;
  request.set_lease_id(impl_->current_lease_id());
  request.set_expires_ns(impl_->to_server_ns(core::monotonic_ns() + core::s_to_ns(valid_for_s)));
  request.mutable_joint_velocity()->mutable_qd()->Assign(qd.data(), qd.data() + qd.size());
  v1::JogResponse response;
  const grpc::Status status = impl_->call(&Stub::Jog, request, &response, true);
  if (!status.ok()) return impl_->error("jog", status);
  return jog_ack(response);
}

Result<TrajectoryAck> RobotClient::execute(const std::string& trajectory_id,
                                           const core::TimedWaypoints& waypoints) {
  v1::ExecuteTrajectoryRequest request;
  request.set_lease_id(impl_->current_lease_id());
  fill_trajectory_request(trajectory_id, waypoints, request);
  v1::ExecuteTrajectoryResponse response;
  const grpc::Status status = impl_->call(&Stub::ExecuteTrajectory, request, &response, true);
  if (!status.ok()) return impl_->error("execute", status);
  return TrajectoryAck{response.trajectory_id(), response.duplicate(),
                       from_proto(response.status()), response.duration_s()};
}

namespace {

PlanAck plan_ack(const v1::ExecutePlanResponse& response) {
  return PlanAck{response.plan_id(), response.duplicate(), from_proto(response.status()),
                 response.duration_s(), plan_hash_hex(response.plan_hash())};
}

}  // namespace

Result<PlanAck> RobotClient::execute_plan(const std::string& plan_id,
                                          const core::Trajectory& trajectory) {
  v1::ExecutePlanRequest request;
  request.set_lease_id(impl_->current_lease_id());
  if (Status s = fill_plan_message(plan_id, trajectory, *request.mutable_plan()); !s) {
    return Error{"execute plan: " + s.error().message};
  }
  v1::ExecutePlanResponse response;
  const grpc::Status status = impl_->call(&Stub::ExecutePlan, request, &response, true);
  if (!status.ok()) return impl_->error("execute plan", status);
  return plan_ack(response);
}

Result<PlanAck> RobotClient::execute_plan(const std::string& plan_id,
                                          const std::vector<core::JointWaypoint>& waypoints,
                                          const core::TrajectoryOptions& options,
                                          const std::string& plan_hash) {
  auto digest = plan_hash_bytes(plan_hash);
  if (!digest) return Error{"execute plan: " + digest.error().message};
  v1::ExecutePlanRequest request;
  request.set_lease_id(impl_->current_lease_id());
  fill_plan_waypoints(plan_id, waypoints, options, *request.mutable_plan());
  request.mutable_plan()->set_plan_hash(std::move(*digest));
  v1::ExecutePlanResponse response;
  const grpc::Status status = impl_->call(&Stub::ExecutePlan, request, &response, true);
  if (!status.ok()) return impl_->error("execute plan", status);
  return plan_ack(response);
}

Result<PlanPreview> RobotClient::preview_plan(const std::string& plan_id,
                                              const std::vector<core::JointWaypoint>& waypoints,
                                              const core::TrajectoryOptions& options,
                                              bool with_samples) {
  v1::PreviewPlanRequest request;
  fill_plan_waypoints(plan_id, waypoints, options, *request.mutable_plan());
  request.set_with_samples(with_samples);
  v1::PreviewPlanResponse response;
  // Not a command: it moves nothing (and the plan message it prepares is counted when sent).
  const grpc::Status status = impl_->call(&Stub::PreviewPlan, request, &response, false);
  if (!status.ok()) return impl_->error("preview plan", status);
  PlanPreview preview;
  preview.plan_id = response.plan_id();
  preview.plan_hash = plan_hash_hex(response.plan_hash());
  preview.algorithm = response.algorithm();
  preview.duration_s = response.duration_s();
  preview.samples_omitted = response.samples_omitted();
  for (const v1::Waypoint& w : response.samples()) {
    preview.samples.times.push_back(core::ns_to_s(w.time_from_start_ns()));
    preview.samples.q.emplace_back(Eigen::Map<const Eigen::VectorXd>(w.q().data(), w.q_size()));
  }
  for (const v1::GripperCommand& g : response.gripper()) {
    preview.samples.gripper.push_back(
        core::GripperEvent{core::ns_to_s(g.time_from_start_ns()), g.opening()});
  }
  return preview;
}

Status RobotClient::cancel(const std::string& reason) {
  v1::CancelRequest request;
  request.set_lease_id(impl_->current_lease_id());
  request.set_reason(reason);
  v1::CancelResponse response;
  const grpc::Status status = impl_->call(&Stub::Cancel, request, &response, true);
  if (!status.ok()) return impl_->error("cancel", status);
  return Status::Ok();
}

void RobotClient::set_ghost(const Eigen::VectorXd& q, double gripper) {
  std::lock_guard lock(impl_->mutex);
  if (impl_->ghost_version != 0 && q.size() == impl_->ghost_q.size() && q == impl_->ghost_q &&
      gripper == impl_->ghost_gripper) {
    return;
  }
  impl_->ghost_q = q;
  impl_->ghost_gripper = gripper;
  ++impl_->ghost_version;
}

Status RobotClient::set_gripper(double opening) {
  v1::SetGripperRequest request;
  request.set_lease_id(impl_->current_lease_id());
  request.set_opening(opening);
  v1::SetGripperResponse response;
  const grpc::Status status = impl_->call(&Stub::SetGripper, request, &response, true);
  if (!status.ok()) return impl_->error("set gripper", status);
  return Status::Ok();
}

Status RobotClient::estop(const std::string& reason) {
  v1::EStopRequest request;
  request.set_reason(reason);
  v1::EStopResponse response;
  const grpc::Status status = impl_->call(&Stub::EStop, request, &response, true);
  if (!status.ok()) return impl_->error("e-stop", status);
  return Status::Ok();
}

Status RobotClient::reset_estop() {
  v1::ResetEStopRequest request;
  request.set_lease_id(impl_->current_lease_id());
  v1::ResetEStopResponse response;
  const grpc::Status status = impl_->call(&Stub::ResetEStop, request, &response, true);
  if (!status.ok()) return impl_->error("reset e-stop", status);
  return Status::Ok();
}

std::uint64_t RobotClient::command_bytes_sent() const {
  return impl_->command_bytes;
}

}  // namespace telear::net
