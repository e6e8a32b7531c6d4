#pragma once
// How a client reaches a telear server: address, credentials, reconnect policy.

#include <string>

namespace telear::net {

struct ClientOptions {
  std::string address;  // "host:port"
  std::string token;    // bearer token; empty: none (observer, where the server allows it)
  std::string client_name = "telear-client";  // shown in the server's log and lease holder
  std::string tls_root_certificate_file;      // empty: plaintext; otherwise TLS with this CA
  // Reconnect with exponential back-off after a stream breaks: initial * factor^n, capped
  // (telear/net/client_base.hpp).
  double reconnect_initial_backoff_s = 0.05;
  double reconnect_backoff_factor = 2.0;
  double reconnect_max_backoff_s = 2.0;
  double rpc_timeout_s = 2.0;  // deadline of each unary call
};

}  // namespace telear::net
