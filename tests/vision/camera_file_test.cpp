#include "telear/vision/camera_file.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <opencv2/core.hpp>

#include "telear/core/pose.hpp"
#include "test_util/test_util.hpp"

namespace telear::vision {
namespace {

CameraModel camera(double x) {
  CameraModel c;
  c.width = 640;
  c.height = 480;
  c.fx = 812.5123456789;
  c.fy = 809.25;
  c.cx = 331.7;
  c.cy = 236.2;
  c.alpha_c = 0.001;
  c.kc = Distortion::plumb_bob(-0.29, 0.11, 0.0011, -0.0007, -0.02);
  c.T_cam_base = core::pose_from_xyz_rpy({x, -0.2, 1.5}, {2.1, 0.1, -0.3});
  return c;
}

void expect_same(const CameraModel& a, const CameraModel& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_LT((a.K() - b.K()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(a.kc.model, b.kc.model);
  EXPECT_EQ(a.kc.coefficients(), b.kc.coefficients());
  EXPECT_LT((a.T_cam_base.matrix() - b.T_cam_base.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + name;
}

std::string error_of(const std::string& text) {
  Result<CameraFile> r = parse_camera_yaml(text, "cam.yaml");
  EXPECT_FALSE(r.ok()) << text;
  return r.ok() ? "" : r.error().message;
}

const char* kMono = R"(%YAML:1.0
---
image_width: 640
image_height: 480
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 800., 0., 319.5, 0., 800., 239.5, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.3, 0.1, 0., 0., 0. ]
)";

TEST(CameraFile, OpenCvMonoRoundTripsExactly) {
  const CameraModel c = camera(0.1);
  const std::string path = temp_path("mono.yaml");
  ASSERT_TRUE(write_camera_file(c, path).ok());
  Result<CameraFile> read = load_camera_file(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_FALSE(read->is_stereo());
  EXPECT_TRUE(read->left_has_pose);
  expect_same(read->left, c);
  // OpenCV itself reads the file back.
  cv::FileStorage fs(path, cv::FileStorage::READ);
  cv::Mat K, D, T;
  fs["camera_matrix"] >> K;
  fs["distortion_coefficients"] >> D;
  fs["T_cam_base"] >> T;
  EXPECT_EQ(static_cast<int>(fs["image_width"]), 640);
  EXPECT_DOUBLE_EQ(K.at<double>(0, 0), c.fx);
  EXPECT_DOUBLE_EQ(K.at<double>(0, 1), c.skew());
  EXPECT_DOUBLE_EQ(D.at<double>(0, 4), -0.02);
  EXPECT_DOUBLE_EQ(T.at<double>(0, 3), 0.1);
  std::remove(path.c_str());
}

TEST(CameraFile, StereoInOneFileAndInTwoFiles) {
  const StereoCameraModel pair{camera(0.03), camera(-0.03)};
  const std::string path = temp_path("stereo.yaml");
  ASSERT_TRUE(write_stereo_camera_file(pair, path).ok());
  Result<CameraFile> read = load_camera_file(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  ASSERT_TRUE(read->is_stereo());
  expect_same(read->left, pair.left);
  expect_same(*read->right, pair.right);

  const std::string l = temp_path("l.yaml"), r = temp_path("r.yaml");
  ASSERT_TRUE(write_camera_file(pair.left, l).ok());
  ASSERT_TRUE(write_camera_file(pair.right, r).ok());
  Result<CameraFile> two = load_stereo_camera_files(l, r);
  ASSERT_TRUE(two.ok()) << two.error().message;
  expect_same(two->left, pair.left);
  expect_same(*two->right, pair.right);
  Result<CameraFile> wrong = load_stereo_camera_files(path, r);
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.error().message,
            "camera file '" + path + "': is a stereo file; give one camera per file");
  for (const std::string& p : {path, l, r}) std::remove(p.c_str());
}

TEST(CameraFile, HandWrittenOpenCvFileWithoutPose) {
  Result<CameraFile> read = parse_camera_yaml(kMono, "cam.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_FALSE(read->left_has_pose);
  EXPECT_TRUE(read->left.T_cam_base.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_DOUBLE_EQ(read->left.kc.k1, -0.3);
  EXPECT_DOUBLE_EQ(read->left.cx, 319.5);
}

TEST(CameraFile, RosCameraInfoRoundTripsAndIsReadWithoutPose) {
  const CameraModel c = camera(0.2);
  Result<CameraFile> read = parse_camera_yaml(ros_camera_info_yaml(c, "left"), "ros.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  expect_same(read->left, c);
  EXPECT_TRUE(read->left_has_pose);

  // What ROS's camera_calibration writes (no T_cam_base, 5 plumb_bob coefficients).
  const char* ros = R"(image_width: 640
image_height: 480
camera_name: narrow_stereo
camera_matrix:
  rows: 3
  cols: 3
  data: [533.0, 0.0, 341.5, 0.0, 533.1, 234.3, 0.0, 0.0, 1.0]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.288, 0.097, 0.0011, -0.0003, 0.0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [533.0, 0.0, 341.5, 0.0, 0.0, 533.1, 234.3, 0.0, 0.0, 0.0, 1.0, 0.0]
)";
  Result<CameraFile> ros_read = parse_camera_yaml(ros, "ros.yaml");
  ASSERT_TRUE(ros_read.ok()) << ros_read.error().message;
  EXPECT_FALSE(ros_read->left_has_pose);
  EXPECT_DOUBLE_EQ(ros_read->left.fy, 533.1);
  EXPECT_DOUBLE_EQ(ros_read->left.kc.p1, 0.0011);
}

TEST(CameraFile, ErrorsNameTheFieldAndWhy) {
  auto with = [](const std::string& from, const std::string& to) {
    std::string text = kMono;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  EXPECT_EQ(error_of(with("image_width: 640\n", "")),
            "camera file 'cam.yaml': image_width: missing");
  EXPECT_EQ(error_of(with("image_height: 480", "image_height: big")),
            "camera file 'cam.yaml': image_height: must be an integer, got 'big'");
  EXPECT_EQ(error_of(with("image_height: 480", "image_height: -4")),
            "camera file 'cam.yaml': image_height must be in [1, 16384], got -4");
  EXPECT_EQ(error_of(with("   rows: 3\n   cols: 3", "   rows: 2\n   cols: 3")),
            "camera file 'cam.yaml': camera_matrix.data: expected 6 numbers (2x3), got 9");
  EXPECT_EQ(error_of(with("data: [ 800., 0., 319.5, 0., 800., 239.5, 0., 0., 1. ]",
                          "data: [ 800., 0., 319.5, 0., 800., 239.5, 0., 0., 1., 0, 0, 0 ]")),
            "camera file 'cam.yaml': camera_matrix.data: expected 9 numbers (3x3), got 12");
  EXPECT_EQ(error_of(with("800., 0., 319.5", "800., 0., abc")),
            "camera file 'cam.yaml': camera_matrix.data[2]: must be a number, got 'abc'");
  EXPECT_EQ(error_of(with("800., 0., 319.5", "-800., 0., 319.5")),
            "camera file 'cam.yaml': camera_matrix: fx ([0][0]) must be positive");
  EXPECT_EQ(error_of(with("0., 0., 1. ]", "0., 0., 2. ]")),
            "camera file 'cam.yaml': camera_matrix: must be [fx s cx; 0 fy cy; 0 0 1] ([1][0], "
            "[2][0], [2][1] zero and [2][2] one)");
  EXPECT_EQ(error_of(with("   cols: 5\n   dt: d\n   data: [ -0.3, 0.1, 0., 0., 0. ]",
                          "   cols: 6\n   dt: d\n   data: [ -0.3, 0.1, 0., 0., 0., 0. ]")),
            "camera file 'cam.yaml': distortion_coefficients: expected 4, 5, 8, 12 or 14 "
            "coefficients, got 6");
  EXPECT_EQ(error_of(with("   cols: 5\n   dt: d\n   data: [ -0.3, 0.1, 0., 0., 0. ]",
                          "   cols: 8\n   dt: d\n   data: [ -0.3, 0.1, 0., 0., 0., 0.2, 0, 0 ]")),
            "camera file 'cam.yaml': distortion_coefficients: coefficient 5 is not zero; "
            "plumb_bob models k1, k2, p1, p2, k3 only (set distortion_model: "
            "rational_polynomial for k4..k6)");
  EXPECT_EQ(error_of(with("image_width: 640", "image_width: 640\ndistortion_model: equidistant")),
            "camera file 'cam.yaml': distortion_coefficients: equidistant takes 4 coefficients "
            "(k1, k2, k3, k4), got 5");
  EXPECT_EQ(error_of(with("image_width: 640", "image_width: 640\ndistortion_model: kb8")),
            "camera file 'cam.yaml': distortion_model: unknown distortion model 'kb8' (expected "
            "plumb_bob, rational_polynomial or equidistant)");
  EXPECT_EQ(error_of(with("image_width: 640",
                          "image_width: 640\nT_cam_base: [1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, "
                          "0, 0, 1]")),
            "camera file 'cam.yaml': T_cam_base: the rotation part is not orthonormal (|R R^T - "
            "I| = 1.73)");
  EXPECT_EQ(error_of(with("image_width: 640",
                          "image_width: 640\nT_cam_base: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, "
                          "0, 0, 1]")),
            "camera file 'cam.yaml': T_cam_base: the rotation part is a reflection (determinant "
            "-1)");
  EXPECT_EQ(error_of(with("image_width: 640", "image_width: 640\nT_cam_base: [1, 0, 0]")),
            "camera file 'cam.yaml': T_cam_base: expected a 4x4 matrix, got 1x3");
  EXPECT_EQ(error_of(with("camera_matrix: !!opencv-matrix", "camera_matrix: [oops\nfoo: 1")),
            "camera file 'cam.yaml': not valid YAML at line 6: end of sequence flow not found");
  EXPECT_EQ(error_of("- 1\n- 2\n"), "camera file 'cam.yaml': the file must be a YAML map");
  EXPECT_EQ(error_of(std::string("left:\n") + "  image_width: 640\n"),
            "camera file 'cam.yaml': right: missing (a stereo file needs left and right)");
  EXPECT_EQ(error_of("left: 3\nright: 4\n"),
            "camera file 'cam.yaml': left: must be a map of image_width, image_height, "
            "camera_matrix, ...");
}

TEST(CameraFile, MissingFile) {
  Result<CameraFile> r = load_camera_file("/nonexistent/cam.yaml");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "cannot open camera file '/nonexistent/cam.yaml'");
}

TEST(CameraFile, ShippedPumaStereoRigLoads) {
  Result<CameraFile> r = load_camera_file(test::data_path("cameras/puma560_stereo.yaml"));
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->is_stereo());
  EXPECT_TRUE(r->left_has_pose && r->right_has_pose);
  EXPECT_EQ(r->left.width, 640);
  EXPECT_EQ(r->left.height, 480);
  // The two optical centres are 6 cm apart.
  const Eigen::Vector3d left_centre = r->left.T_cam_base.inverse().translation();
  const Eigen::Vector3d right_centre = r->right->T_cam_base.inverse().translation();
  EXPECT_NEAR((left_centre - right_centre).norm(), 0.06, 1e-9);
}

}  // namespace
}  // namespace telear::vision
