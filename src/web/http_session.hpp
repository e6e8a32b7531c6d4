#pragma once
// The templates behind connections.hpp, for its two units only: a tab's WebSocket
// (SocketChannel) and the HTTP session before it (HttpSession), over a Stream that is
// beast::tcp_stream or beast::ssl_stream<beast::tcp_stream>.

#include <boost/asio/ssl/stream_base.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <deque>
#include <optional>

#include "connections.hpp"
#include "telear/web/page_files.hpp"

namespace telear::web::connection {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

inline constexpr std::size_t kMaxRequestBody = 64 * 1024;    // the page only GETs
inline constexpr std::size_t kMaxSocketMessage = 64 * 1024;  // a command line, a token
inline constexpr std::size_t kMaxQueuedOnce = 256;           // answers a tab has not read yet
inline constexpr auto kHttpTimeout = std::chrono::seconds(30);

// [SECTION] one tab's WebSocket

template <class Stream>
class SocketChannel : public std::enable_shared_from_this<SocketChannel<Stream>> {
 public:
  SocketChannel(Stream&& stream, std::shared_ptr<const Shared> shared)
      : ws_(std::move(stream)), shared_(std::move(shared)) {}

  ~SocketChannel() {
    if (operator_) operator_->stop();  // its destructor then waits for the session's end
    shared_->tabs.fetch_sub(1);        // the slot taken when the upgrade was accepted
  }

  void start(http::request<http::string_body> request) {
    beast::get_lowest_layer(ws_).expires_never();
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& response) {
      response.set(http::field::server, "telear web");
    }));
    ws_.read_message_max(kMaxSocketMessage);
    ws_.async_accept(
        request, beast::bind_front_handler(&SocketChannel::on_accept, this->shared_from_this()));
  }

  // From any thread: queued on this connection's strand.
  // Queues `data` on the socket's thread. `self` is moved into the posted handler: the
  // operator's threads (its own, the video's receive thread) hold a channel only for this
  // call, so that their reference is never the last one -- the channel owns the operator, and
  // its destructor joins the operator's thread, which must not happen on that thread ("Resource
  // deadlock avoided", seen once in CI when a test ended while a tab was sending).
  static void enqueue(std::shared_ptr<SocketChannel> self, std::string data, bool binary,
                      OperatorOutbox::Kind kind) {
    const auto executor = self->ws_.get_executor();
    asio::post(executor, [self = std::move(self), data = std::move(data), binary, kind]() mutable {
      self->queue(std::move(data), binary, kind);
    });
  }

 private:
  struct Outgoing {
    std::string data;
    bool binary = false;
    OperatorOutbox::Kind kind = OperatorOutbox::Kind::kOnce;
  };

  // The operator's side of the socket: a weak reference, so that the channel (which owns the
  // operator) is not kept alive by it.
  class Outbox : public OperatorOutbox {
   public:
    explicit Outbox(std::weak_ptr<SocketChannel> channel) : channel_(std::move(channel)) {}
    void send_text(std::string message, Kind kind) override {
      if (auto c = channel_.lock()) enqueue(std::move(c), std::move(message), false, kind);
    }
    void send_binary(std::string message, Kind kind) override {
      if (auto c = channel_.lock()) enqueue(std::move(c), std::move(message), true, kind);
    }

   private:
    std::weak_ptr<SocketChannel> channel_;
  };

  void on_accept(beast::error_code ec) {
    if (ec) return;
    operator_ = std::make_unique<BrowserOperator>(shared_->setup,
                                                  std::make_shared<Outbox>(this->weak_from_this()));
    read();
  }

  void read() {
    ws_.async_read(buffer_,
                   beast::bind_front_handler(&SocketChannel::on_read, this->shared_from_this()));
  }

  void on_read(beast::error_code ec, std::size_t) {
    if (ec) {  // closed, or a message over the limit: the tab's session ends
      operator_->stop();
      return;
    }
    if (ws_.got_text()) {
      operator_->receive(beast::buffers_to_string(buffer_.data()));
    } else {
      queue(result_message(-1, false, "binary messages are not read: send JSON text"), false,
            OperatorOutbox::Kind::kOnce);
    }
    buffer_.consume(buffer_.size());
    read();
  }

  void queue(std::string data, bool binary, OperatorOutbox::Kind kind) {
    if (closed_) return;
    if (kind != OperatorOutbox::Kind::kOnce) {
      // Latest wins: a state or a frame still waiting is replaced (never the one being written).
      for (std::size_t i = writing_ ? 1 : 0; i < queue_.size(); ++i) {
        if (queue_[i].kind == kind) {
          queue_[i].data = std::move(data);
          return;
        }
      }
    } else if (queue_.size() >= kMaxQueuedOnce) {
      // A tab that reads nothing: dropped rather than holding its answers without bound (the
      // socket closed under the pending write and read, which then end with an error).
      closed_ = true;
      beast::get_lowest_layer(ws_).close();
      return;
    }
    queue_.push_back({std::move(data), binary, kind});
    if (!writing_) write();
  }

  void write() {
    writing_ = true;
    ws_.binary(queue_.front().binary);
    ws_.async_write(asio::buffer(queue_.front().data),
                    beast::bind_front_handler(&SocketChannel::on_write, this->shared_from_this()));
  }

  void on_write(beast::error_code ec, std::size_t) {
    queue_.pop_front();
    writing_ = false;
    if (ec) {
      closed_ = true;
      return;
    }
    if (!queue_.empty()) write();
  }

  websocket::stream<Stream> ws_;
  std::shared_ptr<const Shared> shared_;
  beast::flat_buffer buffer_;
  std::deque<Outgoing> queue_;
  bool writing_ = false;
  bool closed_ = false;
  std::unique_ptr<BrowserOperator> operator_;
};

// [SECTION] HTTP: the page's files, and the upgrade to the tab's WebSocket

inline http::response<http::string_body> response_with(
    const http::request<http::string_body>& request, http::status status, std::string body,
    const std::string& type) {
  http::response<http::string_body> response{status, request.version()};
  response.set(http::field::server, "telear web");
  response.set(http::field::content_type, type);
  response.set(http::field::cache_control, "no-cache");
  response.set("X-Content-Type-Options", "nosniff");
  response.set("Referrer-Policy", "no-referrer");
  response.keep_alive(request.keep_alive());
  response.body() = std::move(body);
  response.prepare_payload();
  return response;
}

inline http::response<http::string_body> text_response(
    const http::request<http::string_body>& request, http::status status, std::string body) {
  return response_with(request, status, std::move(body), "text/plain; charset=utf-8");
}

inline http::response<http::string_body> page_response(
    const Shared& shared, const http::request<http::string_body>& request) {
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    auto response = text_response(request, http::status::method_not_allowed,
                                  "telear web serves the page's files: GET only\n");
    response.set(http::field::allow, "GET, HEAD");
    return response;
  }
  const std::string target(request.target());
  auto file = read_page_file(shared.page_root, target);
  if (!file) {
    return text_response(request, http::status::not_found, "no such page file: " + target + "\n");
  }
  auto response =
      response_with(request, http::status::ok, std::move(file->body), file->content_type);
  if (request.method() == http::verb::head) response.body().clear();
  return response;
}

template <class Stream>
class HttpSession : public std::enable_shared_from_this<HttpSession<Stream>> {
 public:
  HttpSession(Stream&& stream, std::shared_ptr<const Shared> shared)
      : stream_(std::move(stream)), shared_(std::move(shared)) {}

  void run() {
    if constexpr (std::is_same_v<Stream, beast::tcp_stream>) {
      asio::dispatch(stream_.get_executor(),
                     beast::bind_front_handler(&HttpSession::read, this->shared_from_this()));
    } else {
      beast::get_lowest_layer(stream_).expires_after(kHttpTimeout);
      stream_.async_handshake(asio::ssl::stream_base::server,
                              [self = this->shared_from_this()](beast::error_code ec) {
                                if (!ec) self->read();
                              });
    }
  }

 private:
  void read() {
    parser_.emplace();
    parser_->body_limit(kMaxRequestBody);
    beast::get_lowest_layer(stream_).expires_after(kHttpTimeout);
    http::async_read(stream_, buffer_, *parser_,
                     beast::bind_front_handler(&HttpSession::on_read, this->shared_from_this()));
  }

  void on_read(beast::error_code ec, std::size_t) {
    if (ec) return close();
    http::request<http::string_body> request = parser_->release();
    if (websocket::is_upgrade(request)) {
      const std::string target(request.target());
      if (target.substr(0, target.find('?')) == "/ws") {
        if (shared_->tabs.fetch_add(1) < shared_->max_tabs) {
          std::make_shared<SocketChannel<Stream>>(std::move(stream_), shared_)
              ->start(std::move(request));
          return;
        }
        shared_->tabs.fetch_sub(1);
        response_ = text_response(request, http::status::service_unavailable,
                                  "telear web: " + std::to_string(shared_->max_tabs) +
                                      " tabs are connected, the most it serves (--max-tabs)\n");
        http::async_write(
            stream_, *response_,
            beast::bind_front_handler(&HttpSession::on_write, this->shared_from_this()));
        return;
      }
    }
    response_ = page_response(*shared_, request);
    http::async_write(stream_, *response_,
                      beast::bind_front_handler(&HttpSession::on_write, this->shared_from_this()));
  }

  void on_write(beast::error_code ec, std::size_t) {
    if (ec) return close();
    const bool keep_alive = response_->keep_alive();
    response_.reset();
    if (keep_alive) return read();
    close();
  }

  void close() {
    beast::error_code ignored;
    beast::get_lowest_layer(stream_).socket().shutdown(tcp::socket::shutdown_send, ignored);
  }

  Stream stream_;
  std::shared_ptr<const Shared> shared_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::optional<http::response<http::string_body>> response_;
};

}  // namespace telear::web::connection
