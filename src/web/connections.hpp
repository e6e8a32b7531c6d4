#pragma once
// telear web's connections (web_server.hpp): the HTTP session that serves the page's files and
// upgrades /ws to a tab's WebSocket, whose BrowserOperator it owns. Internal to the web layer.
//
// One template per transport -- plain TCP and TLS -- and each is instantiated in a unit of its
// own (plain_connections.cpp, tls_connections.cpp): Asio and Beast make each instantiation
// ~30 s of compile time, which two units spread over two cores.

#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <memory>
#include <string>

#include "telear/web/browser_operator.hpp"

namespace telear::web {

// Everything a connection needs from the server, shared.
struct Shared {
  std::shared_ptr<const OperatorSetup> setup;
  std::string page_root;
  int max_tabs = 16;
  mutable std::atomic<int> tabs{0};  // sockets open (each one a slot until its channel ends)
};

// Serves one accepted connection until it closes (returns at once; the connection runs on
// the socket's executor, a strand of its own).
void serve_plain(boost::asio::ip::tcp::socket socket, std::shared_ptr<const Shared> shared);
void serve_tls(boost::asio::ip::tcp::socket socket, boost::asio::ssl::context& tls,
               std::shared_ptr<const Shared> shared);

}  // namespace telear::web
