// Door: the robot server's requests, as any client on the network sends them. The first byte
// picks the RPC; the rest is that request's protobuf bytes (structure-aware: protobuf's own
// parser turns the mutated bytes into a message with fields, so the inputs reach telear's
// validation instead of dying in the parser). Each request goes through a real gRPC channel to
// a RobotServer in this process -- the simulated PUMA 560, its collision authority and the
// shipped table workspace -- from a client that holds the lease, so it reaches the lease
// check, the validation and the driver. The selector's top bit keeps the input's own lease id
// (the wrong-lease paths); otherwise the held lease's id is put in.
//
// Besides crashes, sanitizer reports and hangs, the harness checks the server's promise
// (docs/network.md): a command that failed validation never moves the robot. Before each
// input the arm is at rest; after a refused Jog, ExecuteTrajectory or ExecutePlan it must
// still be at rest where it was, or the harness aborts. After each input the arm is stopped
// and an e-stop reset, so every input starts from the same kind of state.

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <thread>

#include <google/protobuf/stubs/logging.h>

#include "fuzz_input.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/net/robot_server.hpp"
#include "telear/net/server_log.hpp"
#include "telear/sim/sim_robot_driver.hpp"
#include "telear/v1/robot.grpc.pb.h"

namespace {

using namespace telear;

constexpr const char* kToken = "fuzz-token";

struct Rig {
  core::RobotDriver* driver = nullptr;  // owned by the server
  std::unique_ptr<net::RobotServer> server;
  std::unique_ptr<v1::RobotService::Stub> stub;
  std::string lease_id;
};

std::unique_ptr<grpc::ClientContext> context() {
  auto c = std::make_unique<grpc::ClientContext>();
  c->AddMetadata("authorization", std::string("Bearer ") + kToken);
  c->AddMetadata("telear-client", "fuzz");
  c->set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  return c;
}

void acquire_lease(Rig& rig) {
  v1::AcquireLeaseRequest request;
  request.set_client_name("fuzz");
  request.set_heartbeat_period_ns(5'000'000'000);  // the longest: inputs may be slow
  v1::Lease lease;
  if (rig.stub->AcquireLease(context().get(), request, &lease).ok()) {
    rig.lease_id = lease.lease_id();
  }
}

Rig& rig() {
  static Rig* made = [] {
    auto* r = new Rig;
    // The server's log of every refused request is no finding, and at thousands of requests a
    // second it would be most of the harness's time: errors only.
    net::log_to_stderr("robot_rpc_fuzz", spdlog::level::err);
    const char* data_dir = std::getenv("TELEAR_DATA_DIR");
    const std::string data = data_dir != nullptr ? data_dir : TELEAR_FUZZ_DATA_DIR;
    auto description = core::load_robot_description({data + "/robots/puma560.yaml"});
    if (!description) std::abort();
    sim::SimRobotDriverOptions driver_options;
    driver_options.robot.initial_q = Eigen::VectorXd::Zero(6);
    driver_options.robot.initial_q << 0.0, 0.5, -0.5, 0.0, 0.5, 0.0;
    auto driver = sim::SimRobotDriver::create(description->model, driver_options);
    if (!driver) std::abort();
    r->driver = driver->get();
    net::RobotServerOptions options;
    options.listen_address = "127.0.0.1:0";
    options.token = kToken;
    options.shutdown_deadline_s = 0.2;
    options.robot_description = *description;
    options.workspace_file = data + "/workspaces/puma560_table.yaml";
    auto server = net::RobotServer::create(std::move(*driver), std::move(options));
    if (!server) std::abort();
    r->server = std::move(*server);
    r->stub = v1::RobotService::NewStub(
        grpc::CreateChannel(r->server->address(), grpc::InsecureChannelCredentials()));
    acquire_lease(*r);
    return r;
  }();
  return *made;
}

// At rest again: a motion the input started is stopped, an e-stop reset, the lease renewed
// (or taken again when the input released it).
void settle(Rig& r) {
  if (r.driver->snapshot().state.mode == core::RobotMode::kEStopped) (void)r.driver->reset_estop();
  if (r.driver->snapshot().state.mode != core::RobotMode::kIdle) r.driver->stop("fuzz: next input");
  for (int i = 0; i < 500 && r.driver->snapshot().state.mode != core::RobotMode::kIdle; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  v1::RenewLeaseRequest renew;
  renew.set_lease_id(r.lease_id);
  v1::Lease lease;
  if (!r.stub->RenewLease(context().get(), renew, &lease).ok()) acquire_lease(r);
}

template <typename Request>
bool parse(Request& request, const std::uint8_t* data, std::size_t size) {
  return request.ParseFromArray(data, static_cast<int>(size));
}

template <typename Request>
void set_lease(Request& request, bool keep_own, const Rig& r) {
  if (!keep_own) request.set_lease_id(r.lease_id);
}

}  // namespace

// protobuf logs every string field that is not UTF-8 as it refuses the message: no finding,
// and at thousands of inputs a second most of the output.
const bool kProtobufQuiet = [] {
  google::protobuf::SetLogHandler(nullptr);
  return true;
}();

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  Rig& r = rig();
  const std::uint8_t selector = data[0];
  const bool keep_own_lease = (selector & 0x80) != 0;
  ++data;
  --size;
  const core::DriverSnapshot before = r.driver->snapshot();
  bool refused_motion = false;
  switch (selector % 12) {
    case 0: {
      v1::JogRequest request;
      if (!parse(request, data, size)) return 0;
      set_lease(request, keep_own_lease, r);
      v1::JogResponse response;
      refused_motion = !r.stub->Jog(context().get(), request, &response).ok();
      break;
    }
    case 1: {
      v1::ExecuteTrajectoryRequest request;
      if (!parse(request, data, size)) return 0;
      set_lease(request, keep_own_lease, r);
      v1::ExecuteTrajectoryResponse response;
      refused_motion = !r.stub->ExecuteTrajectory(context().get(), request, &response).ok();
      break;
    }
    case 2: {
      v1::ExecutePlanRequest request;
      if (!parse(request, data, size)) return 0;
      set_lease(request, keep_own_lease, r);
      v1::ExecutePlanResponse response;
      refused_motion = !r.stub->ExecutePlan(context().get(), request, &response).ok();
      break;
    }
    case 3: {
      v1::PreviewPlanRequest request;
      if (!parse(request, data, size)) return 0;
      v1::PreviewPlanResponse response;
      (void)r.stub->PreviewPlan(context().get(), request, &response);
      break;
    }
    case 4: {
      v1::SetGripperRequest request;
      if (!parse(request, data, size)) return 0;
      set_lease(request, keep_own_lease, r);
      v1::SetGripperResponse response;
      (void)r.stub->SetGripper(context().get(), request, &response);
      break;
    }
    case 5: {
      v1::CancelRequest request;
      if (!parse(request, data, size)) return 0;
      set_lease(request, keep_own_lease, r);
      v1::CancelResponse response;
      (void)r.stub->Cancel(context().get(), request, &response);
      break;
    }
    case 6: {
      v1::EStopRequest request;
      if (!parse(request, data, size)) return 0;
      v1::EStopResponse response;
      (void)r.stub->EStop(context().get(), request, &response);
      break;
    }
    case 7: {
      v1::ResetEStopRequest request;
      if (!parse(request, data, size)) return 0;
      set_lease(request, keep_own_lease, r);
      v1::ResetEStopResponse response;
      (void)r.stub->ResetEStop(context().get(), request, &response);
      break;
    }
    case 8: {
      v1::RenewLeaseRequest request;
      if (!parse(request, data, size)) return 0;
      set_lease(request, keep_own_lease, r);
      v1::Lease response;
      (void)r.stub->RenewLease(context().get(), request, &response);
      break;
    }
    case 9: {
      v1::AcquireLeaseRequest request;
      if (!parse(request, data, size)) return 0;
      v1::Lease response;
      (void)r.stub->AcquireLease(context().get(), request, &response);
      break;
    }
    case 10: {
      v1::ReleaseLeaseRequest request;
      if (!parse(request, data, size)) return 0;
      set_lease(request, keep_own_lease, r);
      v1::ReleaseLeaseResponse response;
      (void)r.stub->ReleaseLease(context().get(), request, &response);
      break;
    }
    default: {
      v1::PingRequest request;
      if (!parse(request, data, size)) return 0;
      v1::PingResponse response;
      (void)r.stub->Ping(context().get(), request, &response);
      v1::RobotInfo info;
      (void)r.stub->GetInfo(context().get(), v1::GetInfoRequest(), &info);
      break;
    }
  }
  if (refused_motion) {
    // A refused motion command left the arm at rest where it was.
    const core::DriverSnapshot after = r.driver->snapshot();
    if (after.state.mode != core::RobotMode::kIdle || after.state.q != before.state.q) {
      std::abort();
    }
  }
  settle(r);
  return 0;
}
