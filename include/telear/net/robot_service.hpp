#pragma once
// The RobotService implementation (proto/telear/v1/robot.proto): the safety authority in
// front of a RobotDriver. Each command passes, in this order,
//
//   authentication (telear/net/bearer_auth.hpp)          -> UNAUTHENTICATED
//   the lease (telear/net/lease_manager.hpp; not EStop)  -> PERMISSION_DENIED
//   validation (telear/net/robot_command_validation.hpp) -> INVALID_ARGUMENT
//   the arm's state (e-stop, busy)                -> FAILED_PRECONDITION
//   collisions (telear/net/motion_collision_guard.hpp)   -> INVALID_ARGUMENT
//
// and only then reaches the driver, so a rejected command never moves the arm. Every command
// is logged once (spdlog, info when accepted, warn when not):
//
//   robot command from alice (ipv4:127.0.0.1:40112): execute trajectory 'p1' (12 waypoints,
//   1.5 s): accepted
//   robot command from bob (ipv4:127.0.0.1:40120): acquire lease: rejected (PERMISSION_DENIED):
//   the lease is held by 'alice'; ...
//
// "Who" is the client's name (metadata `telear-client`, which every telear client sends) and
// its peer address (describe_caller, telear/net/client_name.hpp). A lapsed lease is logged by the
// watchdog, with how late the stop began.
//
// Plans (ExecutePlan, telear/net/plan_message.hpp): the server times the waypoints with core's
// Trajectory::create, compares its plan_hash with the client's, samples the trajectory at
// kPlanExecutionRateHz and executes the samples like a trajectory's; a mismatch, an unknown
// algorithm or an invalid waypoint is INVALID_ARGUMENT and nothing moves.
// PreviewPlan runs the same path (prepare_plan) without comparing the hash and without the
// driver: it answers the hash, the duration and the samples, or ExecutePlan's refusal. It
// needs read access only (authorize_read, like the state), not the lease.
//
// Trajectory ids: the first acceptance of each id is kept, and a repeated id is answered with
// it (duplicate = true, the current status) before any other check but authentication and
// the lease: a retry after a lost reply is safe even when the arm has moved on since.
//
// Threads: the sync gRPC server calls these handlers from its pool; each state stream holds a
// thread while it lasts. begin_shutdown() wakes and ends every stream (UNAVAILABLE, so clients
// reconnect), which lets grpc::Server::Shutdown finish at once.

#include <grpcpp/grpcpp.h>

#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "telear/core/robot_driver.hpp"
#include "telear/net/bearer_auth.hpp"
#include "telear/net/client_name.hpp"
#include "telear/net/lease_manager.hpp"
#include "telear/net/motion_collision_guard.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/net/robot_command_validation.hpp"
#include "telear/v1/robot.grpc.pb.h"

namespace telear::net {

// The rate at which an accepted plan's trajectory is sampled for the driver.
inline constexpr double kPlanExecutionRateHz = 100.0;
// The most samples PreviewPlan returns (300 s at 100 Hz, ~1.7 MB for 6 joints): a longer
// plan is previewed without them (samples_omitted), within gRPC's 4 MB message default.
inline constexpr int kMaxPreviewSamples = 30000;

class RobotService final : public v1::RobotService::Service {
 public:
  // `driver` must outlive the service.
  // Without a guard no motion is collision-checked.
  RobotService(core::RobotDriver& driver, BearerAuth auth, LeaseOptions lease_options,
               CommandLimits limits, std::unique_ptr<MotionCollisionGuard> guard = nullptr);
  ~RobotService() override;

  // Ends every state stream and refuses new ones; stops the lease watchdog.
  void begin_shutdown();

  const LeaseManager& lease() const { return lease_; }

  grpc::Status GetInfo(grpc::ServerContext* context, const v1::GetInfoRequest* request,
                       v1::RobotInfo* response) override;
  grpc::Status StreamState(grpc::ServerContext* context, const v1::StreamStateRequest* request,
                           grpc::ServerWriter<v1::RobotState>* writer) override;
  grpc::Status AcquireLease(grpc::ServerContext* context, const v1::AcquireLeaseRequest* request,
                            v1::Lease* response) override;
  grpc::Status RenewLease(grpc::ServerContext* context, const v1::RenewLeaseRequest* request,
                          v1::Lease* response) override;
  grpc::Status ReleaseLease(grpc::ServerContext* context, const v1::ReleaseLeaseRequest* request,
                            v1::ReleaseLeaseResponse* response) override;
  grpc::Status Jog(grpc::ServerContext* context, const v1::JogRequest* request,
                   v1::JogResponse* response) override;
  grpc::Status ExecuteTrajectory(grpc::ServerContext* context,
                                 const v1::ExecuteTrajectoryRequest* request,
                                 v1::ExecuteTrajectoryResponse* response) override;
  grpc::Status ExecutePlan(grpc::ServerContext* context, const v1::ExecutePlanRequest* request,
                           v1::ExecutePlanResponse* response) override;
  grpc::Status PreviewPlan(grpc::ServerContext* context, const v1::PreviewPlanRequest* request,
                           v1::PreviewPlanResponse* response) override;
  grpc::Status Cancel(grpc::ServerContext* context, const v1::CancelRequest* request,
                      v1::CancelResponse* response) override;
  grpc::Status SetGripper(grpc::ServerContext* context, const v1::SetGripperRequest* request,
                          v1::SetGripperResponse* response) override;
  grpc::Status EStop(grpc::ServerContext* context, const v1::EStopRequest* request,
                     v1::EStopResponse* response) override;
  grpc::Status ResetEStop(grpc::ServerContext* context, const v1::ResetEStopRequest* request,
                          v1::ResetEStopResponse* response) override;
  grpc::Status Ping(grpc::ServerContext* context, const v1::PingRequest* request,
                    v1::PingResponse* response) override;

 private:
  struct FirstAcceptance {
    std::int64_t accepted_ns = 0;
    double duration_s = 0.0;
  };
  // What ExecuteTrajectory and ExecutePlan answer.
  struct Execution {
    bool duplicate = false;
    core::TrajectoryStatus status = core::TrajectoryStatus::kRunning;
    double duration_s = 0.0;
    std::int64_t accepted_ns = 0;
  };

  // A plan as ExecutePlan would run it: the timed trajectory, its hash and its samples.
  struct PreparedPlan {
    ReceivedPlan plan;
    core::TimedWaypoints samples;  // at kPlanExecutionRateHz
  };

  // The first acceptance of `id`, if any (execute_mutex_ held).
  std::optional<Execution> first_acceptance(const std::string& id) const;
  // The arm's state (e-stop, busy, start state) and collisions (execute_mutex_ held); the
  // status is the refusal, if any. `timed`, when given, is what the waypoints sample: it is
  // collision-checked instead of the straight lines between the samples.
  grpc::Status check_motion(const std::string& id, const core::TimedWaypoints& waypoints,
                            const core::Trajectory* timed) const;
  // check_motion, then the driver; records the acceptance (execute_mutex_ held).
  grpc::Status start(const std::string& id, const core::TimedWaypoints& waypoints,
                     const core::Trajectory* timed, Execution& execution);
  // The one path of ExecutePlan and PreviewPlan (execute_mutex_ held): the message checked
  // and timed (plan_from_message, the hash compared or not), sampled, then check_motion.
  // Sets `prepared` when the status is OK.
  grpc::Status prepare_plan(const v1::PlanMessage& plan, PlanHashCheck check,
                            std::optional<PreparedPlan>& prepared) const;

  // Authentication, then the lease; logs and returns the refusal, if any.
  grpc::Status admit(grpc::ServerContext* context, const std::string& what,
                     const std::string& lease_id);
  // The status for a driver rejection: FAILED_PRECONDITION when the arm is busy or
  // e-stopped now, INVALID_ARGUMENT otherwise.
  grpc::StatusCode driver_rejection_code() const;
  grpc::Status finish(grpc::ServerContext* context, const std::string& what, grpc::Status status);
  void on_lease_lapse(const LeaseLapse& lapse);

  core::RobotDriver& driver_;
  const BearerAuth auth_;
  const CommandLimits limits_;
  const std::unique_ptr<MotionCollisionGuard> guard_;  // null: no collision checks
  LeaseManager lease_;

  std::mutex execute_mutex_;  // one trajectory acceptance at a time
  std::map<std::string, FirstAcceptance> accepted_;
  std::map<std::string, std::string> accepted_plan_hashes_;  // plan id -> the server's hash
  mutable std::mutex last_mutex_;
  std::string last_trajectory_id_;  // the latest accepted (for the state's last_trajectory_*)
  // The lease holder's ghost from its latest renewal, streamed while that lease holds.
  struct StreamedGhost {
    std::string lease_id;
    Eigen::VectorXd q;
    double gripper = 0.0;
    std::int64_t received_ns = 0;
  };
  mutable std::mutex ghost_mutex_;
  StreamedGhost ghost_;

  std::mutex shutdown_mutex_;
  std::condition_variable shutdown_cv_;
  bool shutting_down_ = false;
};

}  // namespace telear::net
