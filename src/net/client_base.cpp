#include "telear/net/client_base.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <utility>

#include "telear/core/clock.hpp"
#include "telear/core/number_format.hpp"
#include "telear/net/client_channel.hpp"

namespace telear::net {

ClientBase::ClientBase(const ClientOptions& options, std::string server, int max_receive_bytes)
    : options_(options),
      server_(std::move(server)),
      backoff_(BackoffSchedule::from(options)),
      channel_(make_client_channel(options, max_receive_bytes)) {}

void ClientBase::prepare(grpc::ClientContext& context, bool deadline) const {
  if (!options_.token.empty()) context.AddMetadata("authorization", "Bearer " + options_.token);
  context.AddMetadata(kClientNameMetadata, options_.client_name);
  if (deadline) {
    context.set_deadline(std::chrono::system_clock::now() +
                         std::chrono::nanoseconds(core::s_to_ns(options_.rpc_timeout_s)));
  }
}

Error ClientBase::error(const std::string& command, const grpc::Status& status) const {
  switch (status.error_code()) {
    case grpc::StatusCode::UNAVAILABLE: {
      std::string hint;
      if (!options_.tls_root_certificate_file.empty()) {
        // gRPC says "handshake failed"; the operator needs to know what to check.
        hint = std::ifstream(options_.tls_root_certificate_file).good()
                   ? " (TLS: the server must speak TLS with a certificate signed by the CA in '" +
                         options_.tls_root_certificate_file + "' and naming the host connected to)"
                   : " (TLS: cannot read the CA file '" + options_.tls_root_certificate_file + "')";
      }
      return Error{command + ": " + server_ + " at " + options_.address +
                   " unreachable: " + status.error_message() + hint};
    }
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return Error{command + ": " + server_ + " at " + options_.address +
                   " did not answer within " + core::format_number(options_.rpc_timeout_s) + " s"};
    default:
      // The server's message may already name the command ("acquire lease: ...").
      if (status.error_message().rfind(command + ": ", 0) == 0) {
        return Error{status.error_message()};
      }
      return Error{command + ": " + status.error_message()};
  }
}

bool ClientBase::begin() {
  std::lock_guard lock(mutex_);
  if (running_) return false;
  running_ = true;
  return true;
}

void ClientBase::stop() {
  {
    std::lock_guard lock(mutex_);
    running_ = false;
    if (active_ != nullptr) active_->TryCancel();
  }
  wake_.notify_all();
}

bool ClientBase::running() const {
  std::lock_guard lock(mutex_);
  return running_;
}

bool ClientBase::sleep_while_running(double seconds) {
  std::unique_lock lock(mutex_);
  wake_.wait_for(lock, std::chrono::nanoseconds(core::s_to_ns(seconds)), [&] { return !running_; });
  return running_;
}

void ClientBase::run_stream(const StreamReader& read) {
  int waits = 0;  // back-off waits since the last stream that delivered a message
  bool first = true;
  while (true) {
    grpc::ClientContext context;
    prepare(context, false);
    {
      std::lock_guard lock(mutex_);
      if (!running_) return;
      active_ = &context;
      if (!first) ++stats_.attempts;
    }
    bool delivered = false;
    const grpc::Status status = read(context, [&] {
      last_message_ns_ = core::monotonic_ns();
      if (delivered) return;
      delivered = true;
      waits = 0;
      if (!first) {
        std::lock_guard lock(mutex_);
        ++stats_.successes;
      }
    });
    {
      std::lock_guard lock(mutex_);
      active_ = nullptr;
      // A stream cancelled by stop() is no failure; one the server ended is.
      if (running_) {
        stats_.last_error =
            status.ok() ? "stream: the " + server_ + " at " + options_.address + " ended the stream"
                        : error("stream", status).message;
      }
    }
    first = false;
    if (!sleep_while_running(backoff_.delay_s(waits++))) return;
  }
}

bool ClientBase::connected() const {
  const std::int64_t last = last_message_ns_;
  return last != 0 && core::monotonic_ns() - last < core::s_to_ns(1.0);
}

ReconnectStats ClientBase::reconnect_stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace telear::net
