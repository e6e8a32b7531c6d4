// The TLS instantiation of the connection templates (connections.hpp): HTTPS and WSS.

#include <boost/asio/ssl.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket/ssl.hpp>

#include "connections.hpp"
#include "http_session.hpp"

namespace telear::web {

void serve_tls(boost::asio::ip::tcp::socket socket, boost::asio::ssl::context& tls,
               std::shared_ptr<const Shared> shared) {
  using namespace connection;
  using Stream = beast::ssl_stream<beast::tcp_stream>;
  std::make_shared<HttpSession<Stream>>(Stream(beast::tcp_stream(std::move(socket)), tls),
                                        std::move(shared))
      ->run();
}

}  // namespace telear::web
