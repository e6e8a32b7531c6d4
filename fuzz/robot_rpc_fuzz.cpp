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
#include <optional>
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

Rig* made_rig = nullptr;

Rig& rig() {
  if (made_rig != nullptr) return *made_rig;
  made_rig = [] {
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
  // Shut down before the process's end: LeakSanitizer's exit check (registered before this)
  // found gRPC's worker threads, still serving a live server, holding what they had allocated
  // -- reported after a whole 10^6-input run, on no input of its own.
  std::atexit([] {
    delete made_rig;
    made_rig = nullptr;
  });
  return *made_rig;
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

using Stub = v1::RobotService::Stub;

// One request from the input's bytes, sent with the held lease's id put in (unless the input
// keeps its own); nothing when the bytes are no such message.
template <typename Request, typename Response>
std::optional<grpc::Status> send(Rig& r,
                                 grpc::Status (Stub::*rpc)(grpc::ClientContext*, const Request&,
                                                           Response*),
                                 const std::uint8_t* data, std::size_t size, bool keep_own_lease) {
  Request request;
  if (!request.ParseFromArray(data, static_cast<int>(size))) return std::nullopt;
  if constexpr (requires { request.set_lease_id(std::string()); }) {
    if (!keep_own_lease) request.set_lease_id(r.lease_id);
  }
  Response response;
  return ((*r.stub).*rpc)(context().get(), request, &response);
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
  const bool keep = keep_own_lease;
  std::optional<grpc::Status> status;
  bool motion = false;  // a command that moves the arm when accepted
  switch (selector % 12) {
    case 0:
      status = send(r, &Stub::Jog, data, size, keep);
      motion = true;
      break;
    case 1:
      status = send(r, &Stub::ExecuteTrajectory, data, size, keep);
      motion = true;
      break;
    case 2:
      status = send(r, &Stub::ExecutePlan, data, size, keep);
      motion = true;
      break;
    case 3:
      status = send(r, &Stub::PreviewPlan, data, size, keep);
      break;
    case 4:
      status = send(r, &Stub::SetGripper, data, size, keep);
      break;
    case 5:
      status = send(r, &Stub::Cancel, data, size, keep);
      break;
    case 6:
      status = send(r, &Stub::EStop, data, size, keep);
      break;
    case 7:
      status = send(r, &Stub::ResetEStop, data, size, keep);
      break;
    case 8:
      status = send(r, &Stub::RenewLease, data, size, keep);
      break;
    case 9:
      status = send(r, &Stub::AcquireLease, data, size, keep);
      break;
    case 10:
      status = send(r, &Stub::ReleaseLease, data, size, keep);
      break;
    default: {
      status = send(r, &Stub::Ping, data, size, keep);
      v1::RobotInfo info;
      (void)r.stub->GetInfo(context().get(), v1::GetInfoRequest(), &info);
      break;
    }
  }
  if (!status) return 0;
  const bool refused_motion = motion && !status->ok();
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
