// The client base (telear/net/client_base.hpp) against real servers on 127.0.0.1: the back-off
// schedule, the client name every call carries (both servers log it), and the reconnect
// accounting across a server stopped and started again on the same port.

#include "telear/net/client_base.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "robot_test_support.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/net/vision_server.hpp"
#include "telear/vision/synthetic_source.hpp"

namespace telear::net::test {
namespace {

using ::testing::DoubleEq;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// spdlog's default logger, captured into a string while it lives.
class LogCapture {
 public:
  LogCapture() : previous_(spdlog::default_logger()) {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text_);
    auto logger = std::make_shared<spdlog::logger>("capture", sink);
    logger->set_level(spdlog::level::trace);
    spdlog::set_default_logger(logger);
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  std::string text() {
    spdlog::default_logger()->flush();
    return text_.str();
  }

 private:
  std::shared_ptr<spdlog::logger> previous_;
  std::ostringstream text_;
};

// Waits up to timeout_s for `done`.
template <typename Done>
bool eventually(Done done, double timeout_s = 10.0) {
  const std::int64_t deadline = core::monotonic_ns() + core::s_to_ns(timeout_s);
  while (core::monotonic_ns() < deadline) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

std::vector<double> delays(const BackoffSchedule& schedule, int count) {
  std::vector<double> out;
  for (int n = 0; n < count; ++n) out.push_back(schedule.delay_s(n));
  return out;
}

TEST(BackoffSchedule, GrowsByTheFactorUpToTheCap) {
  const BackoffSchedule defaults = BackoffSchedule::from(ClientOptions{});
  EXPECT_THAT(delays(defaults, 8),
              ElementsAre(DoubleEq(0.05), DoubleEq(0.1), DoubleEq(0.2), DoubleEq(0.4),
                          DoubleEq(0.8), DoubleEq(1.6), DoubleEq(2.0), DoubleEq(2.0)));
  ClientOptions options;
  options.reconnect_initial_backoff_s = 0.1;
  options.reconnect_backoff_factor = 3.0;
  options.reconnect_max_backoff_s = 1.0;
  EXPECT_THAT(
      delays(BackoffSchedule::from(options), 5),
      ElementsAre(DoubleEq(0.1), DoubleEq(0.3), DoubleEq(0.9), DoubleEq(1.0), DoubleEq(1.0)));
  // Far out the power overflows; the cap still holds.
  EXPECT_DOUBLE_EQ(BackoffSchedule::from(options).delay_s(100000), 1.0);
}

TEST(ClientBase, TheRobotServerSeesTheClientName) {
  auto server = start_server();
  LogCapture log;
  RobotClientOptions options;
  options.address = server->address();
  options.token = kToken;
  options.client_name = "probe-alice";
  RobotClient client(options);
  // No lease: rejected, and logged with the caller's name from the metadata.
  EXPECT_FALSE(client.cancel().ok());
  EXPECT_THAT(log.text(), HasSubstr("robot command from probe-alice (ipv4:127.0.0.1:"));
}

TEST(ClientBase, TheVisionServerSeesTheClientName) {
  vision::SyntheticSourceOptions source_options;
  source_options.width = 64;
  source_options.height = 48;
  source_options.fps = 30;
  auto source = vision::SyntheticSource::create(source_options);
  ASSERT_TRUE(source) << source.error().message;
  VisionServerOptions server_options;
  server_options.listen_address = "127.0.0.1:0";
  server_options.source = std::move(*source);
  LogCapture log;
  auto server = VisionServer::create(std::move(server_options));
  ASSERT_TRUE(server) << server.error().message;
  VisionClientOptions options;
  options.address = (*server)->address();
  options.client_name = "probe-bob";
  VisionClient client(options);
  client.start();
  ASSERT_TRUE(client.wait_frame(0, 10.0));
  client.stop();
  EXPECT_TRUE(eventually([&] { return log.text().find("closed") != std::string::npos; }));
  const std::string text = log.text();
  EXPECT_THAT(text, HasSubstr("vision server listening on " + (*server)->address()));
  EXPECT_THAT(text, HasSubstr("vision stream to probe-bob (ipv4:127.0.0.1:"));
  EXPECT_THAT(text, HasSubstr(") opened (shared encode)"));
}

TEST(ClientBase, CountsReconnectAttemptsAndSuccessesAcrossAServerRestart) {
  auto server = start_server();
  const std::string address = server->address();
  RobotClientOptions options;
  options.address = address;
  options.reconnect_initial_backoff_s = 0.02;
  options.reconnect_max_backoff_s = 0.1;
  RobotClient client(options);
  client.start();
  ASSERT_TRUE(client.wait_state(0, 5.0));
  EXPECT_EQ(client.reconnect_stats().attempts, 0u);
  EXPECT_EQ(client.reconnect_stats().last_error, "");

  server->shutdown();
  server.reset();
  // The server is gone: every attempt fails, none succeeds, the last error says why.
  ASSERT_TRUE(eventually([&] { return client.reconnect_stats().attempts >= 3; }));
  ReconnectStats down = client.reconnect_stats();
  EXPECT_EQ(down.successes, 0u);
  EXPECT_THAT(down.last_error, HasSubstr("stream: robot server at " + address + " unreachable"));

  server = start_server(server_options(address));
  ASSERT_NE(server, nullptr);
  ASSERT_TRUE(eventually([&] { return client.reconnect_stats().successes == 1; }));
  const ReconnectStats up = client.reconnect_stats();
  EXPECT_GT(up.attempts, down.attempts);
  EXPECT_TRUE(eventually([&] { return client.connected(); }));
  client.stop();
}

}  // namespace
}  // namespace telear::net::test
