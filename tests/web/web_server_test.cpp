// telear web's server end to end, without a browser: a real WebServer on the embedded
// simulated servers (as `telear web` starts them), spoken to over HTTP and WebSocket by a
// Boost.Beast client. What the page relies on (docs/web.md): the files, the token's refusal
// with its reason, the model, cameras, look-up tables and video after a good token, and every
// action line through the console's code -- including the ones refused in a page.

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "apps/console_command.hpp"
#include "telear/web/web_server.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_pki.hpp"

namespace telear::web {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
namespace ssl = asio::ssl;
using nlohmann::json;

// One tab's socket, read with a timeout; binary messages are counted by kind.
class PageSocket {
 public:
  explicit PageSocket(int port) : ws_(io_) {
    tcp::resolver resolver(io_);
    asio::connect(ws_.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    timeval timeout{0, 200'000};
    setsockopt(ws_.next_layer().native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    ws_.handshake("127.0.0.1:" + std::to_string(port), "/ws");
  }

  void send(const json& message) { ws_.write(asio::buffer(message.dump())); }

  // The first text message for which `match` holds, within `timeout_s` (null json if none).
  json wait_for(const std::function<bool(const json&)>& match, double timeout_s = 10.0) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < deadline) {
      beast::flat_buffer buffer;
      beast::error_code ec;
      ws_.read(buffer, ec);
      if (ec == beast::error::timeout || ec == asio::error::would_block ||
          ec == asio::error::try_again) {
        continue;
      }
      if (ec) ADD_FAILURE() << "socket: " << ec.message();
      if (ec) return nullptr;
      const std::string data = beast::buffers_to_string(buffer.data());
      if (!ws_.got_text()) {
        ++binary_[static_cast<std::uint8_t>(data.at(0))];
        if (data.at(0) == 1) last_frame_ = data;
        continue;
      }
      json message = json::parse(data);
      if (message["type"] == "state") last_state_ = message;
      if (match(message)) return message;
    }
    return nullptr;
  }
  json wait_type(const std::string& type, double timeout_s = 10.0) {
    return wait_for([&](const json& m) { return m["type"] == type; }, timeout_s);
  }
  json command(int id, const std::string& line) {
    send({{"type", "command"}, {"id", id}, {"line", line}});
    return wait_for([&](const json& m) { return m["type"] == "result" && m["id"] == id; });
  }

  int binary_count(int kind) const { return binary_.count(kind) ? binary_.at(kind) : 0; }
  const std::string& last_frame() const { return last_frame_; }
  const json& last_state() const { return last_state_; }

 private:
  asio::io_context io_;
  websocket::stream<tcp::socket> ws_;
  std::map<int, int> binary_;
  std::string last_frame_;
  json last_state_;
};

class WebServerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new std::filesystem::path(std::filesystem::temp_directory_path() /
                                      ("telear_web_test_" + std::to_string(::getpid())));
    std::filesystem::create_directories(*root_);
    std::ofstream(*root_ / "index.html") << "<html>telear</html>";
    WebOptions options;
    options.listen = "127.0.0.1:0";
    options.page_root = root_->string();
    options.resolution = "320x240";
    options.start_local_servers = cli::simulated_local_servers();  // as `telear web`
    auto created = WebServer::create(options, log_);
    ASSERT_TRUE(created) << created.error().message;
    server_ = created->release();
  }
  static void TearDownTestSuite() {
    delete server_;
    server_ = nullptr;
    std::filesystem::remove_all(*root_);
    delete root_;
  }
  void SetUp() override { ASSERT_NE(server_, nullptr); }

  static int port() {
    const std::string url = server_->url();
    return std::stoi(url.substr(url.rfind(':') + 1));
  }
  static http::response<http::string_body> request(http::verb verb, const std::string& target) {
    asio::io_context io;
    beast::tcp_stream stream(io);
    tcp::resolver resolver(io);
    stream.connect(resolver.resolve("127.0.0.1", std::to_string(port())));
    http::request<http::string_body> req{verb, target, 11};
    req.set(http::field::host, "127.0.0.1");
    http::write(stream, req);
    beast::flat_buffer buffer;
    http::response<http::string_body> response;
    http::read(stream, buffer, response);
    return response;
  }
  // A tab connected with the servers' token, its session's first state received.
  static std::unique_ptr<PageSocket> connected_tab() {
    auto tab = std::make_unique<PageSocket>(port());
    tab->send({{"type", "connect"}, {"token", server_->local_token()}});
    EXPECT_FALSE(tab->wait_for([](const json& m) {
                      return m["type"] == "connection" && m["state"] == "connected";
                    })
                     .is_null());
    EXPECT_FALSE(
        tab->wait_for([](const json& m) { return m["type"] == "state" && !m["real"].is_null(); })
            .is_null());
    return tab;
  }

  static inline std::ostringstream log_;
  static inline WebServer* server_ = nullptr;
  static inline std::filesystem::path* root_ = nullptr;
};

TEST_F(WebServerTest, ListensOnTheAskedHostAndPrintsTheToken) {
  EXPECT_EQ(server_->url().rfind("http://127.0.0.1:", 0), 0u) << server_->url();
  EXPECT_GT(port(), 0);
  EXPECT_FALSE(server_->local_token().empty());
}

TEST_F(WebServerTest, ServesThePageAndNothingElse) {
  const auto index = request(http::verb::get, "/");
  EXPECT_EQ(index.result(), http::status::ok);
  EXPECT_EQ(index.body(), "<html>telear</html>");
  EXPECT_EQ(index[http::field::content_type], "text/html; charset=utf-8");
  const auto escape = request(http::verb::get, "/../../etc/passwd");
  EXPECT_EQ(escape.result(), http::status::not_found);
  EXPECT_NE(escape.body().find("no such page file"), std::string::npos);
  const auto post = request(http::verb::post, "/");
  EXPECT_EQ(post.result(), http::status::method_not_allowed);
  EXPECT_EQ(post[http::field::allow], "GET, HEAD");
}

TEST_F(WebServerTest, AWrongTokenIsRefusedWithItsReasonAndCommandsNothing) {
  PageSocket tab(port());
  const json hello = tab.wait_type("hello");
  ASSERT_FALSE(hello.is_null());
  EXPECT_EQ(hello["robot"], "puma560");
  EXPECT_EQ(hello["dof"], 6);
  EXPECT_EQ(hello["embedded"], true);
  tab.send({{"type", "connect"}, {"token", "not-the-token"}});
  const json refused = tab.wait_for(
      [](const json& m) { return m["type"] == "connection" && m["state"] == "refused"; });
  ASSERT_FALSE(refused.is_null());
  EXPECT_EQ(refused["reason"], "wrong token");
  const json result = tab.command(1, "take-control");
  EXPECT_EQ(result["ok"], false);
  EXPECT_EQ(result["message"], "not connected: connect with the token first");
  EXPECT_EQ(tab.binary_count(2), 0) << "the cameras went to a refused tab";

  tab.send({{"type", "connect"}, {"token", ""}});
  const json empty = tab.wait_for(
      [](const json& m) { return m["type"] == "connection" && m["state"] == "refused"; });
  EXPECT_EQ(empty["reason"], "no token: type the servers' token");
}

TEST_F(WebServerTest, TheRightTokenBringsTheArmTheCamerasAndTheVideo) {
  PageSocket tab(port());
  tab.send({{"type", "connect"}, {"token", server_->local_token()}});
  const json model = tab.wait_type("model");
  ASSERT_FALSE(model.is_null());
  EXPECT_GE(model["parts"].size(), 7u);  // base and six links, and the gripper's fingers
  EXPECT_FALSE(model["parts"][1]["vertices"].get<std::string>().empty());
  EXPECT_GE(model["objects"].size(), 1u);  // the floor, and the shipped table's objects
  const json cameras = tab.wait_type("cameras");
  ASSERT_FALSE(cameras.is_null());
  EXPECT_EQ(cameras["width"], 320);
  EXPECT_EQ(cameras["height"], 240);
  ASSERT_EQ(cameras["eyes"].size(), 2u);
  EXPECT_EQ(cameras["eyes"][1]["name"], "right");
  const json state = tab.wait_for(
      [](const json& m) { return m["type"] == "state" && m["fps"].get<double>() > 0.0; }, 20.0);
  ASSERT_FALSE(state.is_null()) << "no video in 20 s";
  EXPECT_EQ(tab.binary_count(2), 2);
  EXPECT_GT(tab.binary_count(1), 0);
  const std::string& frame = tab.last_frame();
  std::uint32_t header_size = 0;
  for (int i = 3; i >= 0; --i)
    header_size = (header_size << 8) | static_cast<std::uint8_t>(frame[4 + i]);
  const json header = json::parse(frame.substr(8, header_size));
  EXPECT_EQ(header["width"], 320);
  const std::size_t left_bytes = header["left_bytes"];
  EXPECT_EQ(frame.substr(8 + header_size, 2), "\xff\xd8");  // a JPEG's start of image
  EXPECT_EQ(frame.substr(8 + header_size + left_bytes, 2), "\xff\xd8");
  EXPECT_EQ(state["robot_connected"], true);
  EXPECT_EQ(state["ghost"].size(), model["parts"].size() * 16);
  EXPECT_EQ(state["real"].size(), model["parts"].size() * 16);
  EXPECT_FALSE(
      tab.wait_for([](const json& m) { return m["type"] == "state" && m["display"] == "ar"; })
          .is_null())
      << "the fresh video never showed in AR";
}

TEST_F(WebServerTest, ActionLinesRunThroughTheConsolesCode) {
  auto tab = connected_tab();
  const double joint2 = tab->last_state()["ghost_q_deg"][1];
  const json moved = tab->command(1, "ghost joint 2 +10deg");
  EXPECT_EQ(moved["ok"], true) << moved["message"];
  EXPECT_NEAR(tab->last_state()["ghost_q_deg"][1].get<double>(), joint2 + 10.0, 1e-9);
  const json added = tab->command(2, "plan add 1.0 end");
  EXPECT_EQ(added["ok"], true) << added["message"];
  EXPECT_EQ(tab->last_state()["plan"]["waypoints"].size(), 1u);
  EXPECT_EQ(tab->last_state()["plan"]["waypoints"][0]["label"], "end");

  const json bad_joint = tab->command(3, "ghost joint 9 +1deg");
  EXPECT_EQ(bad_joint["ok"], false);
  EXPECT_EQ(bad_joint["message"],
            "command, line 1: ghost joint 9 +1deg: joint 9 out of range 1..6");
  const json save = tab->command(4, "plan save /tmp/telear_web_plan.yaml");
  EXPECT_EQ(save["ok"], false);
  EXPECT_NE(save["message"].get<std::string>().find("not in the page"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists("/tmp/telear_web_plan.yaml"));
  const json wait = tab->command(5, "wait 1");
  EXPECT_EQ(wait["ok"], false);
  const json two = tab->command(6, "estop\nreset-estop");
  EXPECT_EQ(two["ok"], false);
  EXPECT_EQ(two["message"], "one action per command line");
  tab->send(json("not an object"));
  const json malformed = tab->wait_type("result");
  EXPECT_EQ(malformed["ok"], false);
  EXPECT_NE(malformed["message"].get<std::string>().find("JSON object"), std::string::npos);
  EXPECT_EQ(tab->command(7, "plan clear")["ok"], true);
}

TEST_F(WebServerTest, OneTabHoldsTheLeaseTheOtherWatchesAndTheEStopLatches) {
  auto first = connected_tab();
  auto second = connected_tab();
  const json taken = first->command(1, "take-control");
  ASSERT_EQ(taken["ok"], true) << taken["message"];
  const json refused = second->command(1, "take-control");
  EXPECT_EQ(refused["ok"], false);
  EXPECT_NE(refused["message"].get<std::string>().find("lease"), std::string::npos)
      << refused["message"];
  EXPECT_FALSE(second
                   ->wait_for([](const json& m) {
                     return m["type"] == "state" && m["in_control"] == false &&
                            !m["real"].is_null();
                   })
                   .is_null());

  const auto pressed = std::chrono::steady_clock::now();
  const json stop = first->command(2, "estop");
  EXPECT_EQ(stop["ok"], true) << stop["message"];
  const json latched = second->wait_for(
      [](const json& m) { return m["type"] == "state" && m["estop"] == true; }, 5.0);
  ASSERT_FALSE(latched.is_null()) << "the watching tab never saw the e-stop";
  EXPECT_EQ(latched["mode"], "estopped");
  std::cout << "e-stop seen by the other tab after "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - pressed).count()
            << " s\n";
  const json reset = first->command(3, "reset-estop");
  EXPECT_EQ(reset["ok"], true) << reset["message"];
  EXPECT_EQ(first->command(4, "release-control")["ok"], true);
}

// HTTPS and WSS with --tls-cert/--tls-key: a browser that trusts the CA gets the page and its
// socket; one that trusts another CA, or speaks plain HTTP, gets nothing.
TEST(WebServerTlsTest, ServesThePageAndTheSocketOnlyOverTls) {
  const test_files::TempDir dir("web_tls");
  const test_files::TestPki pki = test_files::make_test_pki(dir);
  std::ofstream(dir.file("index.html")) << "<html>over tls</html>";
  WebOptions options;
  options.listen = "127.0.0.1:0";
  options.page_root = dir.string();
  options.resolution = "320x240";
  options.tls_cert_file = pki.server_cert;
  options.tls_key_file = pki.server_key;
  options.start_local_servers = cli::simulated_local_servers();
  std::ostringstream log;
  auto server = WebServer::create(options, log);
  ASSERT_TRUE(server) << server.error().message;
  const std::string url = (*server)->url();
  ASSERT_EQ(url.rfind("https://127.0.0.1:", 0), 0u) << url;
  const std::string port = url.substr(url.rfind(':') + 1);

  asio::io_context io;
  tcp::resolver resolver(io);
  const auto endpoints = resolver.resolve("127.0.0.1", port);
  auto tls_stream = [&](const std::string& ca, ssl::context& context) {
    context.load_verify_file(ca);
    context.set_verify_mode(ssl::verify_peer);
    beast::ssl_stream<beast::tcp_stream> stream(io, context);
    stream.set_verify_callback(ssl::rfc2818_verification("127.0.0.1"));
    beast::get_lowest_layer(stream).connect(endpoints);
    beast::get_lowest_layer(stream).expires_after(std::chrono::seconds(10));
    return stream;
  };

  ssl::context trusting(ssl::context::tls_client);
  auto stream = tls_stream(pki.ca, trusting);
  stream.handshake(ssl::stream_base::client);
  http::request<http::string_body> request{http::verb::get, "/", 11};
  request.set(http::field::host, "127.0.0.1");
  http::write(stream, request);
  beast::flat_buffer buffer;
  http::response<http::string_body> response;
  http::read(stream, buffer, response);
  EXPECT_EQ(response.result(), http::status::ok);
  EXPECT_EQ(response.body(), "<html>over tls</html>");

  ssl::context trusting_ws(ssl::context::tls_client);
  websocket::stream<beast::ssl_stream<beast::tcp_stream>> ws(tls_stream(pki.ca, trusting_ws));
  ws.next_layer().handshake(ssl::stream_base::client);
  ws.handshake("127.0.0.1:" + port, "/ws");
  beast::flat_buffer hello;
  ws.read(hello);
  EXPECT_NE(beast::buffers_to_string(hello.data()).find("\"type\":\"hello\""), std::string::npos);

  ssl::context distrusting(ssl::context::tls_client);
  auto other = tls_stream(pki.other_ca, distrusting);
  beast::error_code ec;
  other.handshake(ssl::stream_base::client, ec);
  EXPECT_TRUE(ec) << "a client trusting another CA completed the handshake";

  beast::tcp_stream plain(io);
  plain.connect(endpoints);
  plain.expires_after(std::chrono::seconds(10));
  http::write(plain, request, ec);
  http::response<http::string_body> plain_response;
  beast::flat_buffer plain_buffer;
  if (!ec) http::read(plain, plain_buffer, plain_response, ec);
  EXPECT_TRUE(ec) << "plain HTTP was answered: " << plain_response.result_int();
}

TEST(WebServerOptionsTest, RefusesWhatCannotBeServedAndSaysWhy) {
  std::ostringstream log;
  const test_files::TempDir dir("web_options");
  std::ofstream(dir.file("index.html")) << "<html></html>";
  auto refused = [&](WebOptions options) {
    if (options.page_root.empty()) options.page_root = dir.string();
    options.start_local_servers = cli::simulated_local_servers();
    auto server = WebServer::create(options, log);
    return server ? std::string("started") : server.error().message;
  };
  WebOptions half;
  half.robot = "127.0.0.1:50051";
  EXPECT_EQ(refused(half),
            "give both the robot and the vision server's address, or neither (local servers)");
  WebOptions no_port;
  no_port.listen = "127.0.0.1";
  EXPECT_EQ(refused(no_port), "listen '127.0.0.1': expected HOST:PORT (e.g. 127.0.0.1:8080)");
  WebOptions bad_port;
  bad_port.listen = "127.0.0.1:99999";
  EXPECT_EQ(refused(bad_port), "listen '127.0.0.1:99999': the port must be a number 0..65535");
  WebOptions key_only;
  key_only.tls_key_file = dir.file("web.key");
  EXPECT_EQ(refused(key_only), "HTTPS needs both the certificate and its key");
  WebOptions no_page;
  no_page.page_root = dir.file("nowhere");
  EXPECT_NE(refused(no_page).find("the page's files (index.html, app.js) are not in"),
            std::string::npos);
  WebOptions missing_cert;
  missing_cert.listen = "127.0.0.1:0";
  missing_cert.tls_cert_file = dir.file("missing.crt");
  missing_cert.tls_key_file = dir.file("missing.key");
  EXPECT_EQ(refused(missing_cert).rfind("certificate '" + dir.file("missing.crt") + "': ", 0), 0u)
      << refused(missing_cert);
  // The port taken by another listener.
  asio::io_context io;
  tcp::acceptor taken(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  WebOptions busy;
  busy.listen = "127.0.0.1:" + std::to_string(taken.local_endpoint().port());
  EXPECT_EQ(refused(busy), "listen " + busy.listen + ": Address already in use");
}

TEST(WebServerTabsTest, TabsBeyondTheLimitAreAnswered503) {
  const test_files::TempDir dir("web_tabs");
  std::ofstream(dir.file("index.html")) << "<html></html>";
  WebOptions options;
  options.listen = "127.0.0.1:0";
  options.page_root = dir.string();
  options.max_tabs = 1;
  options.start_local_servers = cli::simulated_local_servers();
  std::ostringstream log;
  auto server = WebServer::create(options, log);
  ASSERT_TRUE(server) << server.error().message;
  const std::string url = (*server)->url();
  const int port = std::stoi(url.substr(url.rfind(':') + 1));
  auto first = std::make_unique<PageSocket>(port);
  EXPECT_FALSE(first->wait_type("hello").is_null());

  asio::io_context io;
  websocket::stream<tcp::socket> second(io);
  tcp::resolver resolver(io);
  asio::connect(second.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
  websocket::response_type response;
  beast::error_code ec;
  second.handshake(response, "127.0.0.1", "/ws", ec);
  EXPECT_EQ(ec, websocket::error::upgrade_declined) << ec.message();
  // The same upgrade as plain HTTP, to read the answer's text.
  beast::tcp_stream raw(io);
  raw.connect(resolver.resolve("127.0.0.1", std::to_string(port)));
  http::request<http::string_body> upgrade{http::verb::get, "/ws", 11};
  upgrade.set(http::field::host, "127.0.0.1");
  upgrade.set(http::field::connection, "Upgrade");
  upgrade.set(http::field::upgrade, "websocket");
  upgrade.set(http::field::sec_websocket_version, "13");
  upgrade.set(http::field::sec_websocket_key, "dGhlIHNhbXBsZSBub25jZQ==");
  http::write(raw, upgrade);
  beast::flat_buffer buffer;
  http::response<http::string_body> refused;
  http::read(raw, buffer, refused);
  EXPECT_EQ(refused.result(), http::status::service_unavailable);
  EXPECT_EQ(refused.body(), "telear web: 1 tabs are connected, the most it serves (--max-tabs)\n");

  first.reset();  // its slot comes back once its session has ended
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  bool served = false;
  while (!served && std::chrono::steady_clock::now() < deadline) {
    websocket::stream<tcp::socket> third(io);
    asio::connect(third.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    third.handshake(response, "127.0.0.1", "/ws", ec);
    served = !ec;
    if (!served) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(served) << "the closed tab's slot was never given back";
}

}  // namespace
}  // namespace telear::web
