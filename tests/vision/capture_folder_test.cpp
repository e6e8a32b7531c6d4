#include "telear/vision/capture_folder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_util/temp_dir.hpp"

namespace telear::vision {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

CaptureSet two_poses() {
  CaptureSet capture;
  capture.robot = "puma560";
  capture.target = "aruco:DICT_4X4_50:0:0.1";
  for (int p = 0; p < 2; ++p) {
    CapturedPose pose;
    pose.q_commanded = Eigen::VectorXd::Constant(6, 0.1 * p);
    pose.q = pose.q_commanded.array() + 1e-9;
    pose.joint_time_ns = 1'000'000'000LL * (p + 1);
    for (int f = 0; f < 2; ++f) {
      CapturedFrame frame;
      frame.frame_id = 10 * p + f;
      frame.left_time_ns = pose.joint_time_ns + f;
      frame.right_time_ns = pose.joint_time_ns + f + 1000;
      frame.left_image = captured_image_path(p, f, true);
      frame.right_image = captured_image_path(p, f, false);
      pose.frames.push_back(frame);
    }
    capture.poses.push_back(pose);
  }
  return capture;
}

TEST(CaptureFolder, ManifestRoundTripsExactly) {
  const CaptureSet written = two_poses();
  auto read = parse_capture_manifest(capture_manifest_yaml(written), "mem");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->robot, "puma560");
  EXPECT_EQ(read->target, written.target);
  ASSERT_EQ(read->poses.size(), 2u);
  EXPECT_EQ(read->poses[1].q, written.poses[1].q);  // %.17g: bit-exact
  EXPECT_EQ(read->poses[1].q_commanded, written.poses[1].q_commanded);
  EXPECT_EQ(read->poses[1].joint_time_ns, 2'000'000'000LL);
  ASSERT_EQ(read->poses[1].frames.size(), 2u);
  EXPECT_EQ(read->poses[1].frames[1].frame_id, 11u);
  EXPECT_EQ(read->poses[1].frames[1].right_time_ns, 2'000'001'001LL);
  EXPECT_EQ(read->poses[1].frames[1].left_image, "pose_001/left_1.png");
}

TEST(CaptureFolder, WritesAndLoadsAFolderWithItsImages) {
  test_files::TempDir tmp("capture_ok");
  const fs::path folder = tmp.path();
  const CaptureSet capture = two_poses();
  const cv::Mat left(24, 32, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat right(24, 32, CV_8UC3, cv::Scalar(40, 50, 60));
  for (const CapturedPose& pose : capture.poses) {
    for (const CapturedFrame& frame : pose.frames) {
      ASSERT_TRUE(write_captured_images(folder.string(), frame, left, right));
    }
  }
  ASSERT_TRUE(write_capture_manifest(capture, folder.string()));
  auto loaded = load_capture_folder(folder.string());
  ASSERT_TRUE(loaded) << loaded.error().message;
  auto images = read_captured_images(folder.string(), loaded->poses[0].frames[1]);
  ASSERT_TRUE(images) << images.error().message;
  EXPECT_EQ(cv::norm(images->left, left, cv::NORM_INF), 0.0);  // PNG: lossless
  EXPECT_EQ(cv::norm(images->right, right, cv::NORM_INF), 0.0);
}

TEST(CaptureFolder, AMissingImageIsNamedWithWhatToDo) {
  test_files::TempDir tmp("capture_missing");
  const fs::path folder = tmp.path();
  const CaptureSet capture = two_poses();
  const cv::Mat image(8, 8, CV_8UC1, cv::Scalar(0));
  for (const CapturedPose& pose : capture.poses) {
    for (const CapturedFrame& frame : pose.frames) {
      ASSERT_TRUE(write_captured_images(folder.string(), frame, image, image));
    }
  }
  ASSERT_TRUE(write_capture_manifest(capture, folder.string()));
  fs::remove(folder / "pose_001/right_0.png");
  auto loaded = load_capture_folder(folder.string());
  ASSERT_FALSE(loaded);
  EXPECT_THAT(loaded.error().message,
              HasSubstr("poses[1].frames[0].right: image 'pose_001/right_0.png' missing; "
                        "recapture the pose or remove it from capture.yaml"));
}

TEST(CaptureFolder, AFolderWithoutManifestIsRefused) {
  test_files::TempDir tmp("capture_empty");
  const fs::path folder = tmp.path();
  auto loaded = load_capture_folder(folder.string());
  ASSERT_FALSE(loaded);
  EXPECT_THAT(loaded.error().message, HasSubstr("capture.yaml missing or unreadable"));
  auto not_folder = load_capture_folder((folder / "nothing").string());
  ASSERT_FALSE(not_folder);
  EXPECT_THAT(not_folder.error().message, HasSubstr("not a folder"));
}

TEST(CaptureFolder, UnsynchronizedFramesAreRefused) {
  CaptureSet capture = two_poses();
  capture.poses[1].frames[0].right_time_ns += 12'000'000;
  auto read = parse_capture_manifest(capture_manifest_yaml(capture), "cap");
  ASSERT_FALSE(read);
  EXPECT_THAT(read.error().message,
              HasSubstr("capture 'cap': poses[1].frames[0]: unsynchronized: the eyes were "
                        "exposed 12.0 ms apart (at most 5.0 ms)"));
  CaptureReadOptions lenient;
  lenient.max_sync_skew_ns = 20'000'000;
  EXPECT_TRUE(parse_capture_manifest(capture_manifest_yaml(capture), "cap", lenient));
}

TEST(CaptureFolder, BadManifestsAreRefusedWithTheField) {
  const CaptureSet good = two_poses();
  auto refuse = [](const std::string& yaml) {
    auto read = parse_capture_manifest(yaml, "m");
    return read ? std::string("accepted") : read.error().message;
  };
  std::string text = capture_manifest_yaml(good);
  EXPECT_THAT(refuse("telear_capture: 2\nposes: []\n"), HasSubstr("unsupported version 2"));
  EXPECT_THAT(refuse("robot: x\n"), HasSubstr("telear_capture: missing"));
  EXPECT_THAT(refuse("telear_capture: 1\nposes: []\n"), HasSubstr("poses: missing or empty"));
  EXPECT_THAT(refuse("telear_capture: 1\nposes:\n  - q: [0, .nan]\n    frames: []\n"),
              HasSubstr("poses[0].q[1]: must be finite"));
  EXPECT_THAT(refuse("telear_capture: 1\nposes:\n  - q: [0, 1]\n    frames: []\n"),
              HasSubstr("poses[0].frames: missing or empty"));
  EXPECT_THAT(refuse("telear_capture: 1\nposes:\n  - q: [0, 1]\n    frames:\n"
                     "      - {left: ../etc/passwd, right: r.png}\n"),
              HasSubstr("poses[0].frames[0].left: '../etc/passwd' leaves the folder"));
  EXPECT_THAT(refuse("telear_capture: 1\nposes:\n  - q: [0, 1]\n    frames:\n"
                     "      - {left: /tmp/l.png, right: r.png}\n"),
              HasSubstr("must be relative to the folder"));
  EXPECT_THAT(refuse("telear_capture: 1\nposes:\n  - q: [0, 1]\n    frames:\n"
                     "      - {left: l.png, right: r.png}\n  - q: [0, 1, 2]\n    frames:\n"
                     "      - {left: l.png, right: r.png}\n"),
              HasSubstr("poses[1].q: 3 joint values, but poses[0] has 2"));
  EXPECT_THAT(refuse("telear_capture: 1\nposes: [\n"), HasSubstr("not valid YAML"));
}

}  // namespace
}  // namespace telear::vision
