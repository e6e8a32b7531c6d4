#include "telear/web/web_server.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/strand.hpp>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "connections.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/net/token_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/stereo_camera_file.hpp"
#include "telear/web/browser_operator.hpp"
#include "telear/web/page_files.hpp"

namespace telear::web {

namespace {

namespace asio = boost::asio;
namespace ssl = asio::ssl;
using tcp = asio::ip::tcp;
using error_code = boost::system::error_code;

// [SECTION] set-up shared by every tab

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
  error_code ec;
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
    acceptor->async_accept(asio::make_strand(*io), [this](error_code ec, tcp::socket s) {
      if (ec == asio::error::operation_aborted) return;  // stopping
      if (!ec) {
        if (tls) {
          serve_tls(std::move(s), *tls, shared);
        } else {
          serve_plain(std::move(s), shared);
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
    error_code ec;
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
  error_code ec;
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
    auto loaded = vision::load_stereo_cameras(options.calibration);
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
  signals.async_wait([](error_code, int) {});
  signals_io.run();
  stop();
}

void WebServer::stop() {
  std::call_once(impl_->stopped, [this] {
    Impl& m = *impl_;
    asio::post(*m.io, [&m] {
      error_code ignored;
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
