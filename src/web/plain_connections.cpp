// The plain-TCP instantiation of the connection templates (connections.hpp).

#include "connections.hpp"
#include "http_session.hpp"

namespace telear::web {

void serve_plain(boost::asio::ip::tcp::socket socket, std::shared_ptr<const Shared> shared) {
  using namespace connection;
  std::make_shared<HttpSession<beast::tcp_stream>>(beast::tcp_stream(std::move(socket)),
                                                   std::move(shared))
      ->run();
}

}  // namespace telear::web
