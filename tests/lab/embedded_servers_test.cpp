// The embedded default's two servers take one token for everything: commanding the robot and
// reading its state, and reading the video too (it was served to anyone on loopback).

#include <gtest/gtest.h>

#include "telear/core/robot_loader.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"

namespace telear::lab {
namespace {

TEST(EmbeddedServers, TheVideoNeedsTheServersToken) {
  auto model = core::load_robot("puma560");
  ASSERT_TRUE(model) << model.error().message;
  EmbeddedServersOptions options;
  options.token = "the-embedded-token";
  auto servers = EmbeddedServers::create(*model, options);
  ASSERT_TRUE(servers) << servers.error().message;
  auto camera_info = [&](const std::string& token) {
    net::VisionClientOptions client;
    client.address = (*servers)->vision_address();
    client.token = token;
    client.rpc_timeout_s = 5.0;
    return net::VisionClient(client).get_camera_info();
  };
  auto none = camera_info("");
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("no token"), std::string::npos) << none.error().message;
  auto wrong = camera_info("not-it");
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().message.find("wrong token"), std::string::npos) << wrong.error().message;
  EXPECT_TRUE(camera_info("the-embedded-token")) << "the right token was refused";

  net::RobotClientOptions robot;
  robot.address = (*servers)->robot_address();
  robot.token = "not-it";
  auto info = net::RobotClient(robot).get_info();
  ASSERT_FALSE(info);
  EXPECT_EQ(info.error().message, "get info: wrong token");
}

}  // namespace
}  // namespace telear::lab
