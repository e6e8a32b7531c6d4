// Issue 25: TLS is tested, not only offered -- certificates made for the test by Debian's
// openssl (a CA, a server certificate for localhost / 127.0.0.1, another CA, a certificate for
// another host), the robot and vision servers started with them, real clients -- and reading
// needs a token by default (the observer token, --allow-observers).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "robot_test_support.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/net/vision_server.hpp"
#include "telear/vision/synthetic_source.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_pki.hpp"

namespace telear::net {
namespace {

using ::testing::HasSubstr;

using test_files::TestPki;

TestPki make_pki(const test_files::TempDir& dir) {
  return test_files::make_test_pki(dir);
}

std::unique_ptr<RobotServer> tls_robot_server(const std::string& cert, const std::string& key) {
  RobotServerOptions options = test::server_options();
  options.allow_observers = false;  // the default
  options.tls_cert_file = cert;
  options.tls_key_file = key;
  return test::start_server(std::move(options));
}

RobotClientOptions client_options(const RobotServer& server, const std::string& ca,
                                  const std::string& token = test::kToken) {
  RobotClientOptions options;
  options.address = server.address();
  options.token = token;
  options.tls_root_certificate_file = ca;
  options.rpc_timeout_s = 2.0;
  return options;
}

TEST(Tls, ATrustedClientCommandsAndStreamsAndTheTokenIsStillRequired) {
  const test_files::TempDir dir("tls");
  const TestPki pki = make_pki(dir);
  auto server = tls_robot_server(pki.server_cert, pki.server_key);
  ASSERT_TRUE(server);

  RobotClient client(client_options(*server, pki.ca));
  client.start();
  auto info = client.get_info();
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->model_name, "puma560");
  ASSERT_TRUE(client.acquire_lease().ok());
  EXPECT_TRUE(client.wait_state(0, 5.0));  // the state stream over TLS
  EXPECT_TRUE(client.release_lease().ok());
  client.stop();

  // Over TLS, without a token: reading is refused (observers are not allowed by default) and
  // so is commanding.
  RobotClient anonymous(client_options(*server, pki.ca, ""));
  auto refused = anonymous.get_info();
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("no token: this server does not allow observers"));
  Status lease = anonymous.acquire_lease();
  ASSERT_FALSE(lease.ok());
  EXPECT_THAT(lease.error().message, HasSubstr("no token"));
}

TEST(Tls, PlaintextAnUntrustedCaAndAnotherHostNameAreRefused) {
  const test_files::TempDir dir("tls-refused");
  const TestPki pki = make_pki(dir);
  auto server = tls_robot_server(pki.server_cert, pki.server_key);
  ASSERT_TRUE(server);
  for (const std::string& ca : {std::string(), pki.other_ca}) {
    RobotClient client(client_options(*server, ca));
    auto info = client.get_info();
    ASSERT_FALSE(info) << (ca.empty() ? "plaintext" : "another CA");
    EXPECT_THAT(info.error().message, HasSubstr("unreachable"));
    if (!ca.empty()) {
      EXPECT_THAT(info.error().message, HasSubstr("TLS"));
    }
  }
  // A certificate from the trusted CA, but for another host than the one connected to.
  auto elsewhere = tls_robot_server(pki.other_host_cert, pki.other_host_key);
  ASSERT_TRUE(elsewhere);
  RobotClient client(client_options(*elsewhere, pki.ca));
  auto info = client.get_info();
  ASSERT_FALSE(info);
  EXPECT_THAT(info.error().message, HasSubstr("TLS"));
}

TEST(Tls, TheVisionServerStreamsToATrustedClientOnly) {
  const test_files::TempDir dir("tls-vision");
  const TestPki pki = make_pki(dir);
  const std::string token_file = dir.file("token");
  std::ofstream(token_file) << test::kToken << "\n";
  vision::SyntheticSourceOptions source;
  source.width = 64;
  source.height = 48;
  source.fps = 30;
  auto synthetic = vision::SyntheticSource::create(source);
  ASSERT_TRUE(synthetic);
  VisionServerOptions options;
  options.listen_address = "127.0.0.1:0";
  options.source = std::move(*synthetic);
  options.token_file = token_file;
  options.tls_cert_file = pki.server_cert;
  options.tls_key_file = pki.server_key;
  auto server = VisionServer::create(std::move(options));
  ASSERT_TRUE(server) << server.error().message;

  VisionClientOptions trusted;
  trusted.address = (*server)->address();
  trusted.token = test::kToken;
  trusted.tls_root_certificate_file = pki.ca;
  VisionClient client(trusted);
  client.start();
  EXPECT_TRUE(client.wait_frame(0, 5.0));
  client.stop();

  VisionClientOptions plaintext = trusted;
  plaintext.tls_root_certificate_file.clear();
  VisionClient refused(plaintext);
  auto info = refused.get_camera_info();
  ASSERT_FALSE(info);
  EXPECT_THAT(info.error().message, HasSubstr("unreachable"));
}

TEST(ObserverAccess, ReadingNeedsATokenByDefaultAndTheObserverTokenOnlyReads) {
  RobotServerOptions options = test::server_options();
  options.allow_observers = false;  // the default
  options.observer_token = "watcher-token";
  auto server = test::start_server(std::move(options));
  ASSERT_TRUE(server);
  auto stub = test::stub_for(*server);
  v1::RobotInfo info;
  const grpc::Status anonymous = stub->GetInfo(test::context("").get(), {}, &info);
  EXPECT_EQ(anonymous.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_THAT(anonymous.error_message(), HasSubstr("does not allow observers"));
  EXPECT_TRUE(stub->GetInfo(test::context("watcher-token").get(), {}, &info).ok());
  v1::AcquireLeaseRequest request;
  request.set_client_name("watcher");
  v1::Lease lease;
  const grpc::Status command =
      stub->AcquireLease(test::context("watcher-token").get(), request, &lease);
  EXPECT_EQ(command.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_THAT(command.error_message(), HasSubstr("read-only token"));
  EXPECT_TRUE(stub->AcquireLease(test::context().get(), request, &lease).ok());

  // --allow-observers opens reading on purpose; the same token for both is refused.
  RobotServerOptions open = test::server_options();
  auto open_server = test::start_server(std::move(open));  // allow_observers = true
  EXPECT_TRUE(test::stub_for(*open_server)->GetInfo(test::context("").get(), {}, &info).ok());
  RobotServerOptions same = test::server_options();
  same.observer_token = test::kToken;
  sim::SimRobotDriverOptions driver_options;
  auto driver = sim::SimRobotDriver::create(telear::test::puma560(), driver_options);
  ASSERT_TRUE(driver);
  auto refused = RobotServer::create(std::move(*driver), std::move(same));
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("the observer token is the operator's token"));
}

}  // namespace
}  // namespace telear::net
