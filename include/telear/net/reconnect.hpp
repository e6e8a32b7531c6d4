#pragma once
// The reconnect policy and its accounting, the part of the client base
// (telear/net/client_base.hpp) that the clients' public headers show, without gRPC.
//
// Back-off: when a client's stream ends, the client waits, then opens a new one:
//   delay(n) = min(initial * factor^n, cap)   seconds, n = waits since the last stream that
//                                              delivered a message (0, 1, 2, ...)
// from ClientOptions (telear/net/client_options.hpp): initial = reconnect_initial_backoff_s,
// factor = reconnect_backoff_factor, cap = reconnect_max_backoff_s. Defaults: 0.05, 0.1, 0.2,
// 0.4, 0.8, 1.6, 2, 2, ... s.
//
// Accounting: ReconnectStats, the same names for RobotClient and VisionClient.

#include <cstdint>
#include <string>

#include "telear/net/client_options.hpp"

namespace telear::net {

// The back-off schedule (see the header comment); a pure function of n.
struct BackoffSchedule {
  double initial_s = 0.05;
  double factor = 2.0;
  double max_s = 2.0;

  static BackoffSchedule from(const ClientOptions& options);
  // The n-th wait since the last stream that delivered a message (n = 0: the first).
  double delay_s(int n) const;
};

struct ReconnectStats {
  std::uint64_t attempts = 0;   // streams opened after the first
  std::uint64_t successes = 0;  // of those, streams that delivered at least one message
  // Why the latest stream that this client did not stop ended (the transport's or the
  // server's message, or "the ... server at HOST:PORT ended the stream"); empty: none has.
  std::string last_error;
};

}  // namespace telear::net
