// The wire between the page and telear web (docs/web.md), without a socket: base64, the
// binary video and look-up-table messages' layout, the cameras' matrices against the camera
// model, and the page's files (which paths are served and which are refused).

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "telear/render/camera_projection.hpp"
#include "telear/vision/distortion_maps.hpp"
#include "telear/web/operator_messages.hpp"
#include "telear/web/page_files.hpp"

namespace telear::web {
namespace {

using nlohmann::json;

std::uint32_t u32_at(const std::string& bytes, std::size_t offset) {
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = (value << 8) | static_cast<std::uint8_t>(bytes[offset + i]);
  return value;
}

vision::CameraModel distorted_camera() {
  vision::CameraModel camera;
  camera.width = 320;
  camera.height = 240;
  camera.fx = 300.0;
  camera.fy = 302.0;
  camera.cx = 161.5;
  camera.cy = 118.25;
  camera.kc.k1 = -0.25;
  camera.kc.k2 = 0.08;
  camera.T_cam_base.translation() = Eigen::Vector3d(0.1, -0.2, 2.0);
  camera.T_cam_base.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, -0.1).normalized()).toRotationMatrix();
  return camera;
}

TEST(Base64Test, EncodesTheRfc4648Vectors) {
  EXPECT_EQ(base64_encode(""), "");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("foo"), "Zm9v");
  EXPECT_EQ(base64_encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64_encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64_encode(std::string("\xff\x00\xfe", 3)), "/wD+");
}

TEST(OperatorMessagesTest, AVideoFrameCarriesBothJpegsAfterItsHeader) {
  const std::string left = "LEFT-JPEG-BYTES";
  const std::string right = "right";
  net::ReceivedStereoFrame frame;
  frame.frame_id = 42;
  frame.jpeg_left = &left;
  frame.jpeg_right = &right;
  frame.width_left = 640;
  frame.height_left = 480;
  frame.capture_ns_left = 1'500'000;
  frame.capture_ns_right = 1'600'000;
  frame.receive_ns = 2'000'000;
  const std::string message = video_frame_message(frame, 2'500'000);
  ASSERT_GT(message.size(), 8u);
  EXPECT_EQ(message[0], static_cast<char>(BinaryKind::kVideoFrame));
  const std::uint32_t header_size = u32_at(message, 4);
  const json header = json::parse(message.substr(8, header_size));
  EXPECT_EQ(header["frame_id"], 42);
  EXPECT_DOUBLE_EQ(header["capture_ms_left"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(header["capture_ms_right"].get<double>(), 1.6);
  EXPECT_DOUBLE_EQ(header["received_ms"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(header["sent_ms"].get<double>(), 2.5);
  EXPECT_EQ(header["width"], 640);
  EXPECT_EQ(header["left_bytes"], left.size());
  EXPECT_EQ(header["right_bytes"], right.size());
  EXPECT_EQ(message.substr(8 + header_size), left + right);
}

TEST(OperatorMessagesTest, TheLookUpTableIsTheOverlaysOwn) {
  const vision::CameraModel camera = distorted_camera();
  const EyeProjection eye = eye_projection("right", camera);
  const std::string message = lut_message(1, eye);
  EXPECT_EQ(message[0], static_cast<char>(BinaryKind::kLookUpTable));
  EXPECT_EQ(message[1], 1);
  EXPECT_EQ(u32_at(message, 4), 320u);
  EXPECT_EQ(u32_at(message, 8), 240u);
  ASSERT_EQ(message.size(), 12u + 320u * 240u * 2u * sizeof(float));
  const std::vector<float> expected =
      render::raw_overlay_lut(vision::compute_raw_to_pinhole_lut(camera));
  std::vector<float> sent(expected.size());
  std::memcpy(sent.data(), message.data() + 12, sent.size() * sizeof(float));
  EXPECT_EQ(sent, expected);
  // Barrel distortion: the pinhole region is larger than the image, around it.
  EXPECT_LT(eye.region.x0, 0);
  EXPECT_LT(eye.region.y0, 0);
  EXPECT_GT(eye.region.width, 320);
  EXPECT_GT(eye.region.height, 240);
}

// A point of the base frame through the page's matrices lands on the camera's pinhole pixel,
// in the full image and in the raw overlay's region alike.
TEST(OperatorMessagesTest, TheCamerasMatricesProjectLikeTheCamera) {
  vision::CameraModel camera = distorted_camera();
  const EyeProjection eye = eye_projection("left", camera);
  const json cameras = json::parse(cameras_message({eye}));
  ASSERT_EQ(cameras["eyes"].size(), 1u);
  EXPECT_EQ(cameras["width"], 320);
  const json& sent = cameras["eyes"][0];
  EXPECT_EQ(sent["name"], "left");
  auto matrix = [](const json& values) {
    Eigen::Matrix4d m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = values[static_cast<std::size_t>(c * 4 + r)];
    return m;
  };
  const Eigen::Matrix4d P = matrix(sent["projection"]);
  const Eigen::Matrix4d V = matrix(sent["view"]);
  const Eigen::Matrix4d R = matrix(sent["region_projection"]);
  const int x0 = sent["region"]["x0"], y0 = sent["region"]["y0"];
  const int rw = sent["region"]["width"], rh = sent["region"]["height"];
  const Eigen::Vector3d p_base(0.05, 0.1, 0.3);
  const Eigen::Vector3d p_cam = camera.T_cam_base * p_base;
  const double u = camera.fx * p_cam.x() / p_cam.z() + camera.cx;
  const double v = camera.fy * p_cam.y() / p_cam.z() + camera.cy;
  auto pixel = [](const Eigen::Matrix4d& projection, const Eigen::Matrix4d& view,
                  const Eigen::Vector3d& p, int width, int height) {
    const Eigen::Vector4d clip = projection * view * p.homogeneous();
    const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
    return Eigen::Vector2d((ndc.x() + 1.0) * width / 2.0 - 0.5,
                           (1.0 - ndc.y()) * height / 2.0 - 0.5);
  };
  const Eigen::Vector2d full = pixel(P, V, p_base, 320, 240);
  EXPECT_NEAR(full.x(), u, 1e-3);
  EXPECT_NEAR(full.y(), v, 1e-3);
  const Eigen::Vector2d in_region = pixel(R, V, p_base, rw, rh);
  EXPECT_NEAR(in_region.x() + x0, u, 1e-3);
  EXPECT_NEAR(in_region.y() + y0, v, 1e-3);
}

TEST(OperatorMessagesTest, ConnectionAndResultMessagesSayWhy) {
  const json refused = json::parse(connection_message("refused", "wrong token"));
  EXPECT_EQ(refused["type"], "connection");
  EXPECT_EQ(refused["state"], "refused");
  EXPECT_EQ(refused["reason"], "wrong token");
  EXPECT_FALSE(json::parse(connection_message("connected")).contains("reason"));
  const json result = json::parse(result_message(7, false, "plan add: no \"waypoint\""));
  EXPECT_EQ(result["id"], 7);
  EXPECT_EQ(result["ok"], false);
  EXPECT_EQ(result["message"], "plan add: no \"waypoint\"");
}

class PageFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() /
            ("telear_page_files_" + std::to_string(::getpid()));
    std::filesystem::create_directories(root_ / "assets");
    std::ofstream(root_ / "index.html") << "<html>index</html>";
    std::ofstream(root_ / "app.js") << "export {};";
    std::ofstream(root_ / "assets" / "a.css") << "body{}";
    std::ofstream(root_.parent_path() / "telear_page_files_secret.txt") << "secret";
  }
  void TearDown() override {
    std::filesystem::remove_all(root_);
    std::filesystem::remove(root_.parent_path() / "telear_page_files_secret.txt");
  }
  std::filesystem::path root_;
};

TEST_F(PageFilesTest, ServesTheBundleAndItsIndex) {
  auto index = read_page_file(root_, "/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->body, "<html>index</html>");
  EXPECT_EQ(index->content_type, "text/html; charset=utf-8");
  auto script = read_page_file(root_, "/app.js?v=3");
  ASSERT_TRUE(script);
  EXPECT_EQ(script->content_type, "text/javascript; charset=utf-8");
  auto css = read_page_file(root_, "/assets/a.css");
  ASSERT_TRUE(css);
  EXPECT_EQ(css->content_type, "text/css; charset=utf-8");
  EXPECT_FALSE(read_page_file(root_, "/missing.js"));
  EXPECT_FALSE(read_page_file(root_, "/assets"));  // a folder is not a file
}

TEST_F(PageFilesTest, RefusesEveryPathThatLeavesTheFolder) {
  for (const std::string& target : std::vector<std::string>{
           "/../telear_page_files_secret.txt", "/assets/../../telear_page_files_secret.txt",
           "//etc/passwd", "/assets\\..\\index.html", std::string("/app.js\0.txt", 12), "app.js",
           "", "/%2e%2e/telear_page_files_secret.txt"}) {
    EXPECT_FALSE(read_page_file(root_, target)) << "served: " << target;
  }
}

TEST_F(PageFilesTest, FindsTheGivenRootOrSaysWhereItLooked) {
  auto found = find_page_root(root_.string());
  ASSERT_TRUE(found);
  EXPECT_EQ(*found, root_.string());
  auto missing = find_page_root((root_ / "assets").string());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("index.html"), std::string::npos);
  EXPECT_NE(missing.error().message.find((root_ / "assets").string()), std::string::npos);
}

}  // namespace
}  // namespace telear::web
