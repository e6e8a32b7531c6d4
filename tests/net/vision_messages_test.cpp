// What the vision client makes of a server's messages (telear/net/vision_messages.hpp): a
// server may send anything, and what is not a camera or not a picture is refused by name.
#include "telear/net/vision_messages.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace telear::net {
namespace {

using ::testing::HasSubstr;

void set_intrinsics(telear::v1::CameraIntrinsics& in, double fx) {
  in.set_width(640);
  in.set_height(480);
  in.add_fc(fx);
  in.add_fc(fx);
  in.add_cc(319.5);
  in.add_cc(239.5);
  for (double k : {-0.1, 0.01, 0.0, 0.0, 0.0}) in.add_kc(k);
}

TEST(VisionMessages, CameraInfoFieldsBecomeTheCameras) {
  telear::v1::CameraInfo info;
  info.set_found(true);
  info.set_source("sim");
  set_intrinsics(*info.mutable_left(), 500.0);
  set_intrinsics(*info.mutable_right(), 510.0);
  auto reply = camera_info_reply(info);
  ASSERT_TRUE(reply) << reply.error().message;
  EXPECT_TRUE(reply->found);
  EXPECT_EQ(reply->source, "sim");
  EXPECT_EQ(reply->cameras.left.width, 640);
  EXPECT_DOUBLE_EQ(reply->cameras.left.fx, 500.0);
  EXPECT_DOUBLE_EQ(reply->cameras.right.fy, 510.0);
  EXPECT_DOUBLE_EQ(reply->cameras.left.kc.coefficients()[0], -0.1);
}

// A server's camera that is no camera was taken as it came (a zero focal length divides by
// zero in every projection); now it is refused, the eye and the field named.
TEST(VisionMessages, ACameraThatIsNoCameraIsRefusedByName) {
  telear::v1::CameraInfo info;
  info.set_found(true);
  set_intrinsics(*info.mutable_left(), 500.0);
  set_intrinsics(*info.mutable_right(), 0.0);
  auto reply = camera_info_reply(info);
  ASSERT_FALSE(reply);
  EXPECT_EQ(reply.error().message,
            "vision server camera info, right: fx (camera_matrix[0][0]) must be positive and "
            "finite, got 0");
  info.mutable_left()->set_width(0);
  reply = camera_info_reply(info);
  ASSERT_FALSE(reply);
  EXPECT_EQ(reply.error().message,
            "vision server camera info, left: image_width must be in [1, 16384], got 0");
  info.mutable_left()->set_width(640);
  info.mutable_left()->set_distortion_model("fisheye_v9");
  reply = camera_info_reply(info);
  ASSERT_FALSE(reply);
  EXPECT_THAT(reply.error().message, HasSubstr("vision server camera info, left: "));
  // Not found: no cameras, no error.
  info.set_found(false);
  reply = camera_info_reply(info);
  ASSERT_TRUE(reply);
  EXPECT_FALSE(reply->found);
}

TEST(VisionMessages, TheRigsConfigurationIsKeptOnlyWhenFinite) {
  telear::v1::StereoFrame frame;
  EXPECT_EQ(scene_configuration(frame).size(), 0);
  for (double q : {0.1, 0.2, 0.3}) frame.add_scene_q(q);
  ASSERT_EQ(scene_configuration(frame).size(), 3);
  EXPECT_DOUBLE_EQ(scene_configuration(frame)(2), 0.3);
  frame.add_scene_q(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(scene_configuration(frame).size(), 0);
}

TEST(VisionMessages, ACorruptEyeIsAnErrorNamingIt) {
  JpegEncoder encoder;
  core::Image grey(32, 16, 3);
  std::fill(grey.pixels.begin(), grey.pixels.end(), std::uint8_t{120});
  auto jpeg = encoder.encode(grey, 90);
  ASSERT_TRUE(jpeg) << jpeg.error().message;
  telear::v1::StereoFrame frame;
  frame.mutable_left()->set_jpeg(*jpeg);
  frame.mutable_right()->set_jpeg(jpeg->substr(0, 20));
  JpegDecoder single;
  StereoJpegDecoder pair;
  for (const bool planes : {false, true}) {
    for (StereoJpegDecoder* p : {static_cast<StereoJpegDecoder*>(nullptr), &pair}) {
      auto decoded = decode_stereo_frame(frame, {p, &single}, planes);
      ASSERT_FALSE(decoded);
      EXPECT_THAT(decoded.error().message, ::testing::StartsWith("right eye: "));
    }
  }
  frame.mutable_right()->set_jpeg(*jpeg);
  auto decoded = decode_stereo_frame(frame, {&pair, &single}, false);
  ASSERT_TRUE(decoded) << decoded.error().message;
  EXPECT_EQ(decoded->right.width, 32);
}

}  // namespace
}  // namespace telear::net
