#pragma once
// `telear web`'s server (docs/web.md): HTTP for the page's files and one WebSocket per browser
// tab, each with its own BrowserOperator (browser_operator.hpp), over Boost.Beast; HTTPS and
// WSS when given a certificate. Two I/O threads; each connection's handlers run on a strand
// of its own, so a slow tab never holds up another's E-STOP.
//
// With no server addresses it starts the local servers (`telear web`: the embedded simulated
// robot and rig) and keeps them for its life. The arm, its body, the workspace's objects and,
// where they are known at start (a calibration file, or the embedded rig's cameras), the
// cameras and their lens look-up tables are prepared once, shared by every tab.

#include <memory>
#include <ostream>
#include <string>

#include "telear/core/result.hpp"
#include "telear/web/web_options.hpp"

namespace telear::web {

class WebServer {
 public:
  // Loads the arm, starts the local servers when no addresses are given, binds the address.
  // Errors name what failed: the arm, the calibration, the page's files, the certificate, the
  // address ("listen 127.0.0.1:80: Permission denied").
  static Result<std::unique_ptr<WebServer>> create(const WebOptions& options, std::ostream& log);
  ~WebServer();  // stop()
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // "http://HOST:PORT" (https with a certificate); the bound port when 0 was asked for.
  std::string url() const;
  // The local servers' token, which the operator types in the page; empty with remote servers.
  const std::string& local_token() const;

  // Serves until SIGINT or SIGTERM (or stop() from another thread).
  void run_until_signal();
  // Closes every tab's session (leases released), the listener, then the local servers.
  void stop();

 private:
  struct Impl;
  explicit WebServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace telear::web
