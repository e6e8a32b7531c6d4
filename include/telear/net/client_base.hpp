#pragma once
// ClientBase: what RobotClient (telear/net/robot_client.hpp) and VisionClient
// (telear/net/vision_client.hpp) share, in one place: the channel, the metadata of every call,
// the reconnect back-off of the stream thread and its accounting, and the wording of transport
// errors. Each client holds one and adds its own RPCs.
//
// Metadata. Every call (unary and streaming) carries
//   authorization: Bearer <token>   when options.token is not empty (telear/net/bearer_auth.hpp)
//   telear-client: <client_name>    always; both servers log it beside the peer, e.g.
//                                   "alice (ipv4:127.0.0.1:40112)" (telear/net/client_name.hpp)
// Unary calls get a deadline options.rpc_timeout_s from now; streams get none.
//
// Reconnect back-off. When a stream ends the stream thread waits, then opens a new one:
// min(initial * factor^n, cap) seconds, n = waits since the last stream that delivered a
// message (BackoffSchedule, telear/net/reconnect.hpp; defaults 0.05, 0.1, 0.2, ... 1.6, 2, 2 s),
// so the first try after a working stream breaks comes within `initial`. gRPC's channel uses
// the same initial and cap for its own connection attempts (telear/net/client_channel.hpp).
//
// Reconnect accounting (ReconnectStats; the same names in both clients):
//   attempts    streams opened after the first one
//   successes   of those, the streams that delivered at least one message
//   last_error  why the latest stream that this client did not stop ended (the transport's
//               or the server's message); empty when none has
//
// Threads. run_stream() runs on the client's stream thread until stop(); stop() may be called
// from any thread: it cancels the open stream and wakes sleep_while_running(). Every other
// member may be called from any thread.

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "telear/core/result.hpp"
#include "telear/net/client_name.hpp"
#include "telear/net/client_options.hpp"
#include "telear/net/reconnect.hpp"

namespace telear::net {

class ClientBase {
 public:
  // `server` names the server in errors ("robot server", "vision server"); max_receive_bytes
  // > 0 raises gRPC's 4 MB receive limit (make_client_channel).
  ClientBase(const ClientOptions& options, std::string server, int max_receive_bytes = 0);
  ClientBase(const ClientBase&) = delete;
  ClientBase& operator=(const ClientBase&) = delete;

  const std::shared_ptr<grpc::Channel>& channel() const { return channel_; }

  // The metadata above, and for unary calls (deadline true) the options' deadline.
  void prepare(grpc::ClientContext& context, bool deadline = true) const;

  // A failed call as an Error prefixed by `command`: "COMMAND: robot server at HOST:PORT
  // unreachable: ...", "... did not answer within 2 s", or the server's own message (which
  // already says what and why; not prefixed twice when it starts with "COMMAND: ").
  Error error(const std::string& command, const grpc::Status& status) const;

  // [SECTION] the stream thread
  // Marks the client running; false when it already was.
  bool begin();
  // Not running any more: cancels the open stream, wakes every sleep_while_running().
  void stop();
  bool running() const;
  // Sleeps up to `seconds`; returns at once, false, when stop() is (or was) called.
  bool sleep_while_running(double seconds);

  // `read` opens one stream with the prepared context, reads it to its end calling
  // `on_message` once per message received, and returns the stream's final status.
  using StreamReader = std::function<grpc::Status(grpc::ClientContext& context,
                                                  const std::function<void()>& on_message)>;
  // Until stop(): opens a stream with `read`, and when it ends waits the back-off and opens
  // the next, keeping the reconnect accounting. Returns after stop().
  void run_stream(const StreamReader& read);

  bool connected() const;  // the stream delivered a message within the last second
  ReconnectStats reconnect_stats() const;

 private:
  ClientOptions options_;
  std::string server_;
  BackoffSchedule backoff_;
  std::shared_ptr<grpc::Channel> channel_;

  mutable std::mutex mutex_;  // running_, active_, stats_
  std::condition_variable wake_;
  bool running_ = false;
  grpc::ClientContext* active_ = nullptr;  // the open stream's context
  ReconnectStats stats_;
  std::atomic<std::int64_t> last_message_ns_{0};
};

}  // namespace telear::net
