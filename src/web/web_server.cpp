#include "telear/web/web_server.hpp"

#include <atomic>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "telear/core/image_size.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/net/token_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/web/browser_operator.hpp"
#include "telear/web/page_files.hpp"

namespace telear::web {

// Everything a connection needs from the server, shared (outside the anonymous namespace:
// WebServer::Impl holds it).
struct Shared {
  std::shared_ptr<const OperatorSetup> setup;
  std::string page_root;
  int max_tabs = 16;
  mutable std::atomic<int> tabs{0};  // sockets open (each one a slot until its channel ends)
};

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace ssl = asio::ssl;
using tcp = asio::ip::tcp;

constexpr std::size_t kMaxRequestBody = 64 * 1024;    // the page only GETs
constexpr std::size_t kMaxSocketMessage = 64 * 1024;  // a command line, a token
constexpr std::size_t kMaxQueuedOnce = 256;           // answers a tab has not read yet
const auto kHttpTimeout = std::chrono::seconds(30);

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
  void enqueue(std::string data, bool binary, OperatorOutbox::Kind kind) {
    asio::post(ws_.get_executor(),
               [self = this->shared_from_this(), data = std::move(data), binary, kind]() mutable {
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
      if (auto c = channel_.lock()) c->enqueue(std::move(message), false, kind);
    }
    void send_binary(std::string message, Kind kind) override {
      if (auto c = channel_.lock()) c->enqueue(std::move(message), true, kind);
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

http::response<http::string_body> response_with(const http::request<http::string_body>& request,
                                                http::status status, std::string body,
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

http::response<http::string_body> text_response(const http::request<http::string_body>& request,
                                                http::status status, std::string body) {
  return response_with(request, status, std::move(body), "text/plain; charset=utf-8");
}

http::response<http::string_body> page_response(const Shared& shared,
                                                const http::request<http::string_body>& request) {
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
      stream_.async_handshake(ssl::stream_base::server,
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

// [SECTION] set-up shared by every tab

Result<vision::StereoCameraModel> load_stereo_file(const std::string& path) {
  auto file = vision::load_camera_file(path);
  if (!file) return file.error();
  if (!file->right) return Error{"calibration '" + path + "': not a stereo camera file"};
  return vision::StereoCameraModel{file->left, *file->right};
}

Result<tcp::endpoint> parse_listen(asio::io_context& io, const std::string& listen) {
  const auto colon = listen.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == listen.size()) {
    return Error{"listen '" + listen + "': expected HOST:PORT (e.g. 127.0.0.1:8080)"};
  }
  std::string host = listen.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  const std::string port = listen.substr(colon + 1);
  if (port.find_first_not_of("0123456789") != std::string::npos || port.size() > 5 ||
      std::stoi(port) > 65535) {
    return Error{"listen '" + listen + "': the port must be a number 0..65535"};
  }
  beast::error_code ec;
  tcp::resolver resolver(io);
  const auto results = resolver.resolve(host, port, ec);
  if (ec || results.empty()) {
    return Error{"listen '" + listen + "': cannot resolve '" + host + "': " + ec.message()};
  }
  return results.begin()->endpoint();
}

}  // namespace

struct WebServer::Impl {
  std::unique_ptr<console::LocalServers> local;
  std::shared_ptr<Shared> shared;
  std::optional<ssl::context> tls;
  std::optional<asio::io_context> io;
  std::optional<tcp::acceptor> acceptor;
  std::vector<std::thread> threads;
  std::string host;
  std::string local_token;
  std::once_flag stopped;

  void accept() {
    acceptor->async_accept(asio::make_strand(*io), [this](beast::error_code ec, tcp::socket s) {
      if (ec == asio::error::operation_aborted) return;  // stopping
      if (!ec) {
        if (tls) {
          std::make_shared<HttpSession<beast::ssl_stream<beast::tcp_stream>>>(
              beast::ssl_stream<beast::tcp_stream>(beast::tcp_stream(std::move(s)), *tls), shared)
              ->run();
        } else {
          std::make_shared<HttpSession<beast::tcp_stream>>(beast::tcp_stream(std::move(s)), shared)
              ->run();
        }
      }
      accept();
    });
  }
};

WebServer::WebServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

WebServer::~WebServer() {
  stop();
}

Result<std::unique_ptr<WebServer>> WebServer::create(const WebOptions& options, std::ostream& log) {
  const bool embedded = options.robot.empty() && options.vision.empty();
  if (!embedded && (options.robot.empty() || options.vision.empty())) {
    return Error{"give both the robot and the vision server's address, or neither (local servers)"};
  }
  if (embedded && !options.start_local_servers) {
    return Error{"no robot and vision server addresses, and no local servers to start"};
  }
  if (options.tls_cert_file.empty() != options.tls_key_file.empty()) {
    return Error{"HTTPS needs both the certificate and its key"};
  }
  if (options.max_tabs < 1) return Error{"max_tabs must be at least 1"};
  auto resolution = core::parse_image_size(options.resolution, {64, 48}, {1920, 1080});
  if (!resolution) return Error{"resolution: " + resolution.error().message};
  auto page_root = find_page_root(options.page_root);
  if (!page_root) return page_root.error();

  auto impl = std::make_unique<Impl>();
  auto setup = std::make_shared<OperatorSetup>();
  setup->width = resolution->width;
  setup->height = resolution->height;
  setup->embedded = embedded;

  // [SECTION] HTTPS
  if (!options.tls_cert_file.empty()) {
    impl->tls.emplace(ssl::context::tls_server);
    impl->tls->set_options(ssl::context::default_workarounds | ssl::context::no_sslv2 |
                           ssl::context::no_sslv3 | ssl::context::no_tlsv1 |
                           ssl::context::no_tlsv1_1);
    beast::error_code ec;
    impl->tls->use_certificate_chain_file(options.tls_cert_file, ec);
    if (ec) return Error{"certificate '" + options.tls_cert_file + "': " + ec.message()};
    impl->tls->use_private_key_file(options.tls_key_file, ssl::context::pem, ec);
    if (ec) return Error{"key '" + options.tls_key_file + "': " + ec.message()};
  }

  // [SECTION] the listener (bound before anything starts: a taken port fails at once)
  impl->io.emplace(2);
  auto endpoint = parse_listen(*impl->io, options.listen);
  if (!endpoint) return endpoint.error();
  impl->host = options.listen.substr(0, options.listen.rfind(':'));
  beast::error_code ec;
  impl->acceptor.emplace(*impl->io);
  impl->acceptor->open(endpoint->protocol(), ec);
  if (!ec) impl->acceptor->set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) impl->acceptor->bind(*endpoint, ec);
  if (!ec) impl->acceptor->listen(asio::socket_base::max_listen_connections, ec);
  if (ec) return Error{"listen " + options.listen + ": " + ec.message()};

  // [SECTION] the arm and the scene, drawn alike in every tab
  auto arm = geometry::load_robot_assets(options.arm, options.geometry);
  if (!arm) return arm.error();
  for (const std::string& warning : arm->warnings) log << "telear web: " << warning << "\n";
  setup->model = arm->model();
  setup->body = core::build_arm_body(arm->body);
  setup->objects = {render::make_floor(3.0f, 12)};
  session::SessionOptions& session_options = setup->session_options;
  const std::string workspace_file = options.workspace.empty()
                                         ? core::default_workspace_file(arm->description.name)
                                         : options.workspace;
  if (!options.workspace.empty() || std::filesystem::exists(workspace_file)) {
    auto workspace = geometry::load_workspace(workspace_file);
    if (!workspace) return workspace.error();
    for (render::SceneObject& o : render::workspace_scene_objects(*workspace)) {
      setup->objects.push_back(std::move(o));
    }
    session_options.description = arm->description;
    session_options.workspace = std::move(*workspace);
  }
  if (auto marker = arm->marker()) {
    session_options.marker = session::GripperMarker{marker->id, marker->corners_flange()};
  }
  setup->model_json = model_message(setup->body, setup->objects);

  // [SECTION] the servers and the cameras
  std::optional<vision::StereoCameraModel> cameras;
  if (!options.calibration.empty()) {
    auto loaded = load_stereo_file(options.calibration);
    if (!loaded) return loaded.error();
    cameras = *loaded;
  }
  net::RobotClientOptions& robot = session_options.robot;
  net::VisionClientOptions& vision = session_options.vision;
  std::string token;
  if (!options.token_file.empty()) {
    auto loaded = net::load_token_file(options.token_file);
    if (!loaded) return loaded.error();
    token = *loaded;
  }
  if (embedded) {
    auto servers =
        options.start_local_servers(setup->model, arm->description, options.calibration, token);
    if (!servers) return servers.error();
    impl->local = std::move(*servers);
    if (!cameras) cameras = impl->local->cameras();
    robot.address = impl->local->robot_address();
    vision.address = impl->local->vision_address();
    impl->local_token = impl->local->token();
    session_options.lease_heartbeat_s = 1.0;  // see SessionOptions::lease_heartbeat_s
    log << "telear web: embedded simulated servers: robot " << robot.address << ", vision "
        << vision.address << "\n";
  } else {
    robot.address = options.robot;
    vision.address = options.vision;
    robot.tls_root_certificate_file = options.tls_ca_file;
    vision.tls_root_certificate_file = options.tls_ca_file;
  }
  if (options.lease_heartbeat_s > 0.0)
    session_options.lease_heartbeat_s = options.lease_heartbeat_s;
  vision.width = setup->width;
  vision.height = setup->height;
  // The page decodes the JPEGs it is sent; the session's own decode feeds only the frame's age
  // and the registration check, which reads luma: no colour conversion.
  vision.decode_planes = true;
  if (!cameras && !token.empty()) {  // the vision server's calibration, read with the file's token
    net::VisionClientOptions probe_options = vision;
    probe_options.token = token;
    net::VisionClient probe(probe_options);
    auto info = probe.get_camera_info();
    if (!info) return Error{"no calibration: " + info.error().message + " (give --calibration)"};
    if (!info->found) return Error{"no calibration: the vision server has none; give one"};
    cameras = info->cameras;
  }
  if (cameras) {  // else each tab asks the vision server with its own token
    setup->eyes = std::vector<EyeProjection>{
        eye_projection("left", vision::resized_camera(cameras->left, setup->width, setup->height)),
        eye_projection("right",
                       vision::resized_camera(cameras->right, setup->width, setup->height))};
    session_options.cameras = vision::StereoCameraModel{
        vision::resized_camera(cameras->left, setup->width, setup->height),
        vision::resized_camera(cameras->right, setup->width, setup->height)};
  }

  impl->shared = std::make_shared<Shared>();
  impl->shared->setup = std::move(setup);
  impl->shared->page_root = *page_root;
  impl->shared->max_tabs = options.max_tabs;
  log << "telear web: the page from " << *page_root << "\n";
  impl->accept();
  for (int i = 0; i < 2; ++i) impl->threads.emplace_back([io = &*impl->io] { io->run(); });
  return std::unique_ptr<WebServer>(new WebServer(std::move(impl)));
}

std::string WebServer::url() const {
  const auto port = impl_->acceptor->local_endpoint().port();
  return std::string(impl_->tls ? "https" : "http") + "://" + impl_->host + ":" +
         std::to_string(port);
}

const std::string& WebServer::local_token() const {
  return impl_->local_token;
}

void WebServer::run_until_signal() {
  asio::io_context signals_io;
  asio::signal_set signals(signals_io, SIGINT, SIGTERM);
  signals.async_wait([](beast::error_code, int) {});
  signals_io.run();
  stop();
}

void WebServer::stop() {
  std::call_once(impl_->stopped, [this] {
    Impl& m = *impl_;
    asio::post(*m.io, [&m] {
      beast::error_code ignored;
      m.acceptor->close(ignored);
    });
    m.io->stop();
    for (std::thread& t : m.threads) t.join();
    // Destroying the context destroys every connection, and with it every tab's session,
    // which releases its lease -- while the local servers still run.
    m.acceptor.reset();
    m.io.reset();
    if (m.local) m.local->stop();
  });
}

}  // namespace telear::web
