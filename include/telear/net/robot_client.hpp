#pragma once
// RobotClient: the operator's (or an observer's) side of RobotService (proto/telear/v1/
// robot.proto), in plain C++ types.
//
// Threads. start() opens a state stream on a background thread at options.state_rate_hz; each
// message is converted and published into a latest-wins slot (telear/net/latest_slot.hpp), so
// latest_state() is a lock-light read of the newest state and a slow reader never queues.
// When the stream breaks (server gone, network down) the thread reconnects with exponential
// back-off (telear/net/client_base.hpp, which also sends the token and the client name with
// every call); connected() and reconnect_stats() tell the UI. A second background thread
// pings the server (1 Hz) to estimate the clock offset (telear/net/clock_offset.hpp), so the
// state's age and the jog expiry are computed across machines.
//
// Lease. acquire_lease() takes the lease and starts a heartbeat thread that renews it at a
// third of its period; release_lease() (or destruction) gives it back. If renewal fails the
// lease is reported lost (lease_held() false, lease_error() says why); the server meanwhile
// stops the arm (the dead-man).
//
// Commands are unary calls with options.rpc_timeout_s deadlines; each returns a Result whose
// error message is the server's (it says what and why) prefixed by the command name, or the
// transport's ("robot server at HOST:PORT unreachable: ...").
//
// Every member function may be called from any thread.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/motion_command.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_state.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/net/client_options.hpp"
#include "telear/net/clock_offset.hpp"
#include "telear/net/reconnect.hpp"

namespace telear::net {

struct RobotStateSample;

struct RobotClientOptions : ClientOptions {
  double state_rate_hz = 100.0;  // 1..250
  double ping_period_s = 1.0;
  // Called on the receive thread for every state, before latest_state() can return it (a
  // recorder's: every state, none skipped). Keep it short; it delays the next receive.
  std::function<void(const RobotStateSample&)> on_state;
};

struct JointInfo {
  std::string name;
  bool prismatic = false;
  double min_position = 0, max_position = 0, max_velocity = 0, max_acceleration = 0;
};

struct RobotInfo {
  std::string model_name;
  std::string urdf;
  std::string tip_link;  // with urdf: the chain the server's model follows
  std::vector<JointInfo> joints;
  std::vector<std::pair<std::string, Eigen::VectorXd>> named_configurations;
  std::string driver;
  double heartbeat_period_s = 0.25;
  double start_tolerance = 0.0;
  int max_waypoints = 0;
  // The collision authority (docs/network.md): whether the server checks motions, the
  // workspace file's text it checks against (empty: none) and the jog safety margin.
  bool collision_checked = false;
  std::string workspace_yaml;
  double safety_margin_m = 0.0;
};

// One state message, as the client received it.
struct RobotStateSample {
  core::RobotState
      state;  // telear/core/robot_state.hpp; `time` = capture time in seconds (server clock)
  std::uint64_t sequence = 0;   // this client's count of states received, from 1, across reconnects
  std::int64_t capture_ns = 0;  // server clock
  std::int64_t server_send_ns = 0;  // server clock
  std::int64_t receive_ns = 0;      // client clock
  std::string lease_holder;
  std::string last_trajectory_id;
  core::TrajectoryStatus last_trajectory_status = core::TrajectoryStatus::kRunning;
  std::string last_trajectory_message;
  std::int64_t clock_offset_ns = 0;  // server minus client, the estimate when received
  // The lease holder's ghost (empty: none; v1::RobotState.ghost_q), server clock stamp.
  Eigen::VectorXd ghost_q;
  double ghost_gripper = 0.0;
  std::int64_t ghost_ns = 0;
  // Client clock: capture time converted with the offset estimate (loopback: equal).
  std::int64_t capture_client_ns() const;
};

struct TrajectoryAck {
  std::string trajectory_id;
  bool duplicate = false;
  core::TrajectoryStatus status = core::TrajectoryStatus::kRunning;
  double duration_s = 0.0;
};

// ExecutePlan's answer: the server's hash (equal to the client's: a mismatch is an error).
struct PlanAck {
  std::string plan_id;
  bool duplicate = false;
  core::TrajectoryStatus status = core::TrajectoryStatus::kRunning;
  double duration_s = 0.0;
  std::string plan_hash;
};

// PreviewPlan's answer: what ExecutePlan would run now (telear/net/robot_service.hpp).
struct PlanPreview {
  std::string plan_id;
  std::string plan_hash;  // 64 lowercase hex digits, as core::plan_hash gives it
  std::string algorithm;
  double duration_s = 0.0;
  // The 100 Hz samples the arm would follow, when asked for; empty otherwise, and when the
  // plan is longer than the server returns (samples_omitted).
  core::TimedWaypoints samples;
  bool samples_omitted = false;
};

struct JogAck {
  Eigen::VectorXd target_q;  // empty for a velocity jog
  std::string singularity_warning;
  std::string ik_config;
};

class RobotClient {
 public:
  explicit RobotClient(RobotClientOptions options);
  ~RobotClient();  // releases the lease, stops the threads
  RobotClient(const RobotClient&) = delete;
  RobotClient& operator=(const RobotClient&) = delete;

  const RobotClientOptions& options() const;

  // Starts the state stream and ping threads; returns at once (connection is lazy).
  void start();
  void stop();
  bool connected() const;  // the state stream delivered a message within the last second
  ReconnectStats reconnect_stats() const;  // the state stream's (telear/net/client_base.hpp)

  Result<RobotInfo> get_info();
  std::optional<RobotStateSample> latest_state() const;
  // Waits up to timeout_s for a state newer than `after_sequence` (0: any).
  std::optional<RobotStateSample> wait_state(std::uint64_t after_sequence, double timeout_s) const;
  std::optional<ClockOffset> clock_offset() const;
  // One ping now (also feeds the estimator); returns the round trip in seconds.
  Result<double> ping();

  Status acquire_lease(double heartbeat_period_s = 0.0);  // 0: the server's default
  Status release_lease();
  bool lease_held() const;
  std::string lease_error() const;  // why the lease was lost, empty when held or never taken

  // Jogs with an expiry `valid_for_s` from now (converted to the server's clock).
  Result<JogAck> jog(const core::MotionCommand& command, double valid_for_s = 0.5);
  Result<JogAck> jog_velocity(const Eigen::VectorXd& qd, double valid_for_s = 0.5);
  Result<TrajectoryAck> execute(const std::string& trajectory_id,
                                const core::TimedWaypoints& waypoints);
  // The plan is the message: sends the trajectory's waypoints, options and plan_hash
  // (telear/net/plan_message.hpp); the server times them itself and executes only a match.
  Result<PlanAck> execute_plan(const std::string& plan_id, const core::Trajectory& trajectory);
  // For a client that does not time plans itself: the server times and checks the waypoints
  // as ExecutePlan would now and answers the hash (or ExecutePlan's refusal); no lease
  // needed, nothing moves. Then execute_plan with that hash runs exactly the previewed motion.
  Result<PlanPreview> preview_plan(const std::string& plan_id,
                                   const std::vector<core::JointWaypoint>& waypoints,
                                   const core::TrajectoryOptions& options = {},
                                   bool with_samples = false);
  // The plan message with a hash the caller got elsewhere (preview_plan's), hex.
  Result<PlanAck> execute_plan(const std::string& plan_id,
                               const std::vector<core::JointWaypoint>& waypoints,
                               const core::TrajectoryOptions& options,
                               const std::string& plan_hash);
  Status cancel(const std::string& reason = "cancelled by the operator");
  Status set_gripper(double opening);
  // The ghost the lease's heartbeat carries from now on (each renewal sends the latest), so a
  // driver can show the operator's rehearsal to the arm's own tools (docs/ros.md); sent only
  // while the lease is held, and only when it changed.
  void set_ghost(const Eigen::VectorXd& q, double gripper);
  Status estop(const std::string& reason = "e-stop from the operator");
  Status reset_estop();

  // Bytes of request messages this client serialized (commands only, not the state stream),
  // for the plan-then-send vs streaming comparison.
  std::uint64_t command_bytes_sent() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace telear::net
