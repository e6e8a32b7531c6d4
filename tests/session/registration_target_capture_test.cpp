// Registration with a ChArUco board on the flange (issue 15, "Targets"): the simulated PUMA
// 560 rig draws the board where the marker mount sits (the rig file's `target:`), the capture
// goes through the embedded robot and vision servers at the poses a capture of the ArUco
// marker chose, and both captures are registered and compared with the rig's true cameras
// (both figures printed; docs/registration.md, "Targets").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <thread>
#include <tuple>

#include "capture_test_rig.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/session/registration_capture.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/capture_registration.hpp"
#include "telear/vision/image_file.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "telear/vision/registered_camera_file.hpp"
#include "telear/vision/registration_target.hpp"
#include "test_util/mesh_test_files.hpp"

namespace telear::session {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

constexpr const char* kBoard = "charuco:4x4:0.08:0.05:4x4_50";

// Another seed (other automatic poses) or another target on the flange for the measurements
// in docs/registration.md: TELEAR_CAPTURE_TEST_SEED=N, TELEAR_CAPTURE_TEST_TARGET=SPEC (the
// assertions are the board kBoard's).
std::uint64_t capture_seed() {
  const char* seed = std::getenv("TELEAR_CAPTURE_TEST_SEED");
  return seed ? std::stoull(seed) : 1;
}
// The automatic poses of each capture (the marker's and the target's own):
// TELEAR_CAPTURE_TEST_POSES=N, default 14.
int auto_pose_count() {
  const char* poses = std::getenv("TELEAR_CAPTURE_TEST_POSES");
  return poses ? std::stoi(poses) : 14;
}
std::string board_spec() {
  const char* spec = std::getenv("TELEAR_CAPTURE_TEST_TARGET");
  return spec ? spec : kBoard;
}

struct Errors {
  double left_mm, left_deg, right_mm, right_deg, target_mm;
};

class RegistrationTargetCaptureTest : public test::CaptureRigTest {
 protected:
  void SetUp() override {
    test::CaptureRigTest::SetUp();
    if (HasFatalFailure()) return;
    // The PUMA rig file with the board on the flange: paths made absolute, `target:` added.
    const fs::path rig_file = sim::default_rig_file("puma560");
    std::ifstream in(rig_file);
    std::stringstream text;
    text << in.rdbuf();
    std::string yaml = text.str();
    const std::string relative = ": ../";
    const std::string absolute = ": " + (rig_file.parent_path() / "..").string() + "/";
    for (std::size_t at = yaml.find(relative); at != std::string::npos;
         at = yaml.find(relative, at + absolute.size())) {
      yaml.replace(at, relative.size(), absolute);
    }
    board_rig = (dir / "board_rig.yaml").string();
    std::ofstream(board_rig) << yaml << "target: \"" << board_spec() << "\"\n";
  }

  // Captures through freshly started servers on `rig_file`; auto_poses > 0 or `poses`; the
  // target recorded (and detected for auto poses): unset, the robot's marker.
  RegistrationCaptureResult capture(
      const std::string& rig_file, const std::string& name, const Eigen::VectorXd& start,
      int auto_poses, const std::vector<Eigen::VectorXd>& poses,
      const std::optional<vision::RegistrationTarget>& target = std::nullopt) {
    lab::EmbeddedServersOptions options;
    options.rig = rig_file;
    options.calibration_file = calibration;
    options.initial_q = start;
    options.fps = 10.0;
    // Anti-aliased as a lens blurs: 2 x 2 samples alone put a nearly level edge on a staircase
    // of half pixels, and the marker's corners of such views 0.2-0.35 px off (issue 26 item 1).
    options.supersample = 2;
    options.multisample = 4;
    auto servers = lab::EmbeddedServers::create(model, options);
    EXPECT_TRUE(servers) << servers.error().message;
    if (!servers) return {};
    net::RobotClientOptions robot_options;
    robot_options.address = (*servers)->robot_address();
    robot_options.token = (*servers)->token();
    net::RobotClient robot(robot_options);
    robot.start();
    // A long heartbeat: the test renders two eyes per frame on a shared machine.
    for (int attempt = 0; attempt < 50 && !robot.acquire_lease(2.0); ++attempt) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    net::VisionClientOptions vision_options;
    vision_options.address = (*servers)->vision_address();
    vision_options.token = (*servers)->token();
    vision_options.jpeg_quality = 100;
    net::VisionClient vision(vision_options);
    vision.start();
    RegistrationCaptureOptions capture;
    capture.directory = (dir / name).string();
    capture.auto_poses = auto_poses;
    capture.poses = poses;
    capture.frames_per_pose = 2;
    capture.velocity_scale = 1.0;
    capture.settle_s = 0.1;
    capture.marker = marker;
    capture.target = target;
    capture.seed = capture_seed();
    auto captured = capture_for_registration(*model, robot, vision, capture);
    EXPECT_TRUE(captured) << captured.error().message;
    return captured ? *captured : RegistrationCaptureResult{};
  }

  Errors errors_of(const vision::CaptureRegistration& r) const {
    const auto left = vision::registration_error(rig.cameras.left.T_cam_base, r.result.T_left_base);
    const auto right =
        vision::registration_error(rig.cameras.right.T_cam_base, r.result.T_right_base);
    const double target_mm =
        1000.0 *
        (r.result.T_flange_target.translation() - marker.T_flange_marker.translation()).norm();
    return {left.position_mm, left.rotation_deg, right.position_mm, right.rotation_deg, target_mm};
  }

  // TELEAR_CAPTURE_TEST_DIAG=1: each view's detected points against the true projections of
  // their own target points at the recorded joints (the rig's true cameras, the mount's true
  // pose), beside the solver's per-view RMS: which views pull the registration, and whether
  // their residuals show it (docs/registration.md, "Targets").
  void print_truth_split(const char* label, const vision::CaptureRegistration& r) {
    if (std::getenv("TELEAR_CAPTURE_TEST_DIAG") == nullptr) return;
    core::KinematicsData data(*model);
    const auto& points = r.detected.observations.target_points;
    for (const vision::HandEyeView& view : r.detected.observations.views) {
      core::forward_kinematics(*model, data, view.q);
      const Eigen::Isometry3d T_base_target = data.T_base_link.back() * marker.T_flange_marker;
      std::string line;
      for (auto [eye, camera, pixels] : {std::tuple{"L", &rig.cameras.left, &view.left},
                                         std::tuple{"R", &rig.cameras.right, &view.right}}) {
        double sum = 0.0, worst = 0.0;
        Eigen::Vector2d mean = Eigen::Vector2d::Zero();
        // The scale of the detected points about their centre against the truth's (a bias that
        // moves the target's distance, not its place in the image).
        Eigen::Vector2d centre = Eigen::Vector2d::Zero();
        std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> pairs;  // truth, error
        for (const vision::TargetPixel& p : *pixels) {
          const auto truth =
              camera->project(T_base_target * points[static_cast<std::size_t>(p.point)]);
          if (!truth) continue;
          pairs.emplace_back(*truth, p.pixel - *truth);
          centre += *truth;
        }
        if (!pairs.empty()) centre /= static_cast<double>(pairs.size());
        double along = 0.0, spread = 0.0;
        for (const auto& [truth, error] : pairs) {
          along += error.dot(truth - centre);
          spread += (truth - centre).squaredNorm();
        }
        const double scale = spread > 0.0 ? along / spread : 0.0;
        for (const vision::TargetPixel& p : *pixels) {
          const auto truth =
              camera->project(T_base_target * points[static_cast<std::size_t>(p.point)]);
          if (!truth) continue;
          const Eigen::Vector2d e = p.pixel - *truth;
          sum += e.squaredNorm();
          worst = std::max(worst, e.norm());
          mean += e / static_cast<double>(pixels->size());
        }
        if (std::getenv("TELEAR_CAPTURE_TEST_DIAG")[0] == '2') {
          for (const vision::TargetPixel& p : *pixels) {
            const auto truth =
                camera->project(T_base_target * points[static_cast<std::size_t>(p.point)]);
            if (truth)
              std::printf("  %s %s point %d at (%.2f %.2f): error (%+.3f %+.3f)\n",
                          view.name.c_str(), eye, p.point, truth->x(), truth->y(),
                          p.pixel.x() - truth->x(), p.pixel.y() - truth->y());
          }
        }
        char text[200];
        std::snprintf(text, sizeof text,
                      " %s %zu pts rms %.3f max %.3f mean (%+.3f %+.3f) scale %+.5f;", eye,
                      pixels->size(), pixels->empty() ? 0.0 : std::sqrt(sum / pixels->size()),
                      worst, mean.x(), mean.y(), scale);
        line += text;
      }
      double fit = -1.0;
      for (const vision::ViewFit& f : r.result.views)
        if (f.name == view.name) fit = f.rms_px;
      std::printf("diag %s %s:%s fit %.3f\n", label, view.name.c_str(), line.c_str(), fit);
    }
  }

  std::string board_rig;
};

// The automatic poses the capture replaced because an eye saw too little of the target there.
int replaced(const RegistrationCaptureResult& capture) {
  return static_cast<int>(
      std::count_if(capture.notes.begin(), capture.notes.end(), [](const std::string& note) {
        return note.find("replaced by another pose") != std::string::npos;
      }));
}

TEST_F(RegistrationTargetCaptureTest, AChArUcoBoardOnTheFlangeRegistersAgainstTheTruth) {
  // Start where both cameras see the marker (the operator's jog before an automatic capture).
  auto visible = test::marker_visible_start();
  ASSERT_TRUE(visible) << visible.error().message;
  Eigen::VectorXd start = *visible;

  // The marker, at automatic poses; then the board at the same poses.
  const RegistrationCaptureResult with_marker =
      capture(sim::default_rig_file(), "marker", start, auto_pose_count(), {});
  ASSERT_GE(with_marker.capture.poses.size(), 10u);
  std::vector<Eigen::VectorXd> poses;
  for (const auto& pose : with_marker.capture.poses) poses.push_back(pose.q_commanded);
  auto board_target = vision::parse_registration_target(board_spec());
  ASSERT_TRUE(board_target) << board_target.error().message;
  RegistrationCaptureResult with_board =
      capture(board_rig, "board", start, 0, poses, *board_target);
  ASSERT_EQ(with_board.capture.poses.size(), poses.size());
  // The folder names the board, so that register finds it without --target.
  EXPECT_EQ(with_board.capture.target, board_target->spec());

  auto marker_registration =
      vision::register_captures(*model, (dir / "marker").string(), "", marker);
  ASSERT_TRUE(marker_registration) << marker_registration.error().message;
  auto board_registration = vision::register_captures(*model, (dir / "board").string(), "", marker);
  ASSERT_TRUE(board_registration) << board_registration.error().message;
  EXPECT_EQ(marker_registration->detected.target.kind, vision::TargetKind::kAruco);
  ASSERT_EQ(board_registration->detected.target.kind, board_target->kind);
  for (const auto& note : board_registration->detected.notes)
    std::printf("board: %s\n", note.c_str());
  // Partial views count: the board found at most poses, in both eyes.
  EXPECT_GE(board_registration->detected.left_found, 6);
  EXPECT_GE(board_registration->detected.right_found, 6);
  // The coverage image is green under a board's seen corners.
  const cv::Mat coverage = vision::coverage_image(board_registration->detected,
                                                  rig.cameras.left.width, rig.cameras.left.height);
  ASSERT_TRUE(vision::write_png_file((dir / "board_coverage.png").string(), coverage));
  for (const vision::HandEyeView& view : board_registration->detected.observations.views) {
    if (view.left.size() < 4) continue;
    if (view.left.size() == 4) {  // a marker (TELEAR_CAPTURE_TEST_TARGET): its quad's centre,
      // in its own drawing (another pose's outline may cross it in the whole image)
      vision::CaptureObservations alone = board_registration->detected;
      alone.observations.views = {view};
      const cv::Mat own =
          vision::coverage_image(alone, rig.cameras.left.width, rig.cameras.left.height);
      Eigen::Vector2d centre = Eigen::Vector2d::Zero();
      for (const vision::TargetPixel& p : view.left) centre += 0.25 * p.pixel;
      const cv::Vec3b at =
          own.at<cv::Vec3b>(static_cast<int>(centre.y()), static_cast<int>(centre.x()));
      EXPECT_GT(at[1], at[0]) << view.name << ": no green where the marker was";
      continue;
    }
    // Every pixel inside the hull of the seen corners, off its outline and the dots (1 px discs at
    // the rounded corner): lit in the whole image (another pose's outline or number may cross it),
    // green in this pose's own drawing. (A single probe a quarter along the corners' first-to-last
    // diagonal lay on the outline when a partial view's first and last corners shared a column:
    // seed 2.)
    vision::CaptureObservations alone = board_registration->detected;
    alone.observations.views = {view};
    const cv::Mat own =
        vision::coverage_image(alone, rig.cameras.left.width, rig.cameras.left.height);
    std::vector<cv::Point2f> corners, hull;
    for (const vision::TargetPixel& p : view.left)
      corners.emplace_back(static_cast<float>(p.pixel.x()), static_cast<float>(p.pixel.y()));
    cv::convexHull(corners, hull);
    const cv::Rect box = cv::boundingRect(hull);
    // The pose's label, drawn at the first point of the hull of the rounded corners (as
    // coverage_image rounds them), may lie inside too: its box, with a pixel of anti-aliasing.
    std::vector<cv::Point> rounded, rounded_hull;
    for (const vision::TargetPixel& p : view.left)
      rounded.emplace_back(static_cast<int>(std::lround(p.pixel.x())),
                           static_cast<int>(std::lround(p.pixel.y())));
    cv::convexHull(rounded, rounded_hull);
    int baseline = 0;
    const cv::Size text = cv::getTextSize("0", cv::FONT_HERSHEY_SIMPLEX, 0.35, 1, &baseline);
    const cv::Point label = rounded_hull.front() + cv::Point(2, -3);
    const cv::Rect label_box(label.x - 2, label.y - text.height - 2, text.width + 4,
                             text.height + baseline + 4);
    int inside = 0, dark = 0, not_green = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      for (int x = box.x; x < box.x + box.width; ++x) {
        const cv::Point2f at(static_cast<float>(x), static_cast<float>(y));
        if (cv::pointPolygonTest(hull, at, true) < 2.5) continue;
        bool near_dot = false;
        for (const cv::Point2f& c : corners) near_dot = near_dot || cv::norm(c - at) < 3.5;
        if (near_dot || label_box.contains(cv::Point(x, y))) continue;
        ++inside;
        if (coverage.at<cv::Vec3b>(y, x) == cv::Vec3b(40, 40, 40)) ++dark;
        const cv::Vec3b bgr = own.at<cv::Vec3b>(y, x);
        if (!(bgr[1] > bgr[0] + 40)) ++not_green;
      }
    }
    EXPECT_EQ(dark, 0) << view.name << ": dark where the board was (" << inside << " pixels)";
    EXPECT_EQ(not_green, 0) << view.name << ": no green where the board was (" << inside
                            << " pixels)";
  }

  print_truth_split("marker", *marker_registration);
  print_truth_split("board", *board_registration);
  const Errors m = errors_of(*marker_registration);
  const Errors b = errors_of(*board_registration);
  std::printf("marker: %d automatic poses replaced\n", replaced(with_marker));
  std::printf(
      "%zu poses, seed %llu\n"
      "  marker %-32s left %.3f mm %.4f deg, right %.3f mm %.4f deg, on the flange %.3f mm; rms "
      "%.3f px\n"
      "  board  %-32s left %.3f mm %.4f deg, right %.3f mm %.4f deg, on the flange %.3f mm; rms "
      "%.3f px\n",
      poses.size(), static_cast<unsigned long long>(capture_seed()),
      marker_registration->detected.target.spec().c_str(), m.left_mm, m.left_deg, m.right_mm,
      m.right_deg, m.target_mm, marker_registration->result.left.rms_px,
      board_registration->detected.target.spec().c_str(), b.left_mm, b.left_deg, b.right_mm,
      b.right_deg, b.target_mm, board_registration->result.left.rms_px);
  // Bounds with room for the run-to-run spread (0.14-0.41 mm per eye over seeds 1 and 2 since
  // issue 26's corner refinement, 1.05-2.01 mm before), docs/registration.md, "Targets".
  EXPECT_LT(b.left_mm, 1.0);
  EXPECT_LT(b.right_mm, 1.0);
  EXPECT_LT(b.left_deg, 0.05);
  EXPECT_LT(b.right_deg, 0.05);
  EXPECT_LT(b.target_mm, 0.5);
  // Not asserted: that the board beats the marker. It does at these poses (its corners fit to
  // ~0.05 px against the marker's 0.11 px), but its 12 px markers (1.9 px a cell) decode at
  // only about half of them (docs/registration.md, Targets).

  // A board seen in one eye only at a pose is named, and so is one with too few corners.
  // The pose: where both eyes found the most corners (the weaker eye's count), so that its
  // first frame alone still shows enough of the board (at seed 3 the first pose both eyes
  // found showed 4 corners in one frame's left eye, under the 5 a view needs).
  std::size_t both = 0;
  const auto& views = board_registration->detected.observations.views;
  const auto weaker = [&](std::size_t v) {
    return std::min(views[v].left.size(), views[v].right.size());
  };
  for (std::size_t v = 1; v < views.size(); ++v) {
    if (weaker(v) > weaker(both)) both = v;
  }
  ASSERT_LT(both, views.size());
  ASSERT_GT(weaker(both), 0u);
  if (board_target->is_board()) {  // (TELEAR_CAPTURE_TEST_TARGET may name a marker)
    vision::CaptureSet one_eye = board_registration->capture;
    one_eye.poses = {one_eye.poses[both]};
    one_eye.poses[0].frames.resize(1);
    const std::string blank = "blank.png";
    ASSERT_TRUE(vision::write_png_file((dir / "board" / blank).string(),
                                       cv::Mat(rig.cameras.left.height, rig.cameras.left.width,
                                               CV_8UC3, cv::Scalar(128, 128, 128))));
    one_eye.poses[0].frames[0].right_image = blank;
    auto detected =
        vision::detect_capture_targets((dir / "board").string(), one_eye, *board_target);
    ASSERT_TRUE(detected) << detected.error().message;
    EXPECT_THAT(detected->notes,
                ::testing::Contains("pose 0: the board was seen in the left eye only"));
    vision::CaptureDetectionOptions strict;
    strict.min_corners = 10;  // a 4x4 board has 9
    detected =
        vision::detect_capture_targets((dir / "board").string(), one_eye, *board_target, strict);
    ASSERT_TRUE(detected) << detected.error().message;
    ASSERT_FALSE(detected->notes.empty());
    EXPECT_THAT(detected->notes.front(),
                HasSubstr("corners of the board (fewer than 10): not used"));
    EXPECT_THAT(detected->notes.front(), HasSubstr("pose 0: the left eye saw "));
  }

  // The board's own automatic poses, from a pose where both eyes found it: the rough cameras
  // come from the board, and each pose keeps its whole chessboard in both views with cells of
  // 1.5 px or more. Its markers' 1.9 px cells (seen face on) still fail to decode at some, and
  // the simulator's real shoulder (larger than the nominal body) hides it at others: the
  // capture replaces those by spare poses.
  const Eigen::VectorXd board_start = with_board.capture.poses[both].q;
  const RegistrationCaptureResult board_auto =
      capture(board_rig, "board_auto", board_start, auto_pose_count(), {}, *board_target);
  for (const std::string& note : board_auto.notes) std::printf("board auto: %s\n", note.c_str());
  ASSERT_GE(board_auto.capture.poses.size(), 12u);
  EXPECT_EQ(board_auto.capture.target, board_target->spec());
  auto board_auto_registration =
      vision::register_captures(*model, (dir / "board_auto").string(), "", marker);
  ASSERT_TRUE(board_auto_registration) << board_auto_registration.error().message;
  const vision::CaptureObservations& board_found = board_auto_registration->detected;
  const int captured = static_cast<int>(board_auto.capture.poses.size());
  print_truth_split("board_auto", *board_auto_registration);
  const Errors a = errors_of(*board_auto_registration);
  std::printf(
      "  board, its own %d automatic poses (%d replaced): found %d left / %d right; left %.3f mm "
      "%.4f deg, "
      "right %.3f mm %.4f deg, on the flange %.3f mm; rms %.3f px\n",
      captured, replaced(board_auto), board_found.left_found, board_found.right_found, a.left_mm,
      a.left_deg, a.right_mm, a.right_deg, a.target_mm,
      board_auto_registration->result.left.rms_px);
  // Every pose kept shows the board in both eyes with half its corners or more: the capture
  // replaced those that did not by spare poses (it failed before: 6-8 of 10), and drops one
  // when no spare is left (it kept it before: the AprilTag at seed 1, 20 poses, found 19 of 20).
  EXPECT_EQ(board_found.left_found, captured);
  EXPECT_EQ(board_found.right_found, captured);
  // Issue 26 item 1's goal, the marker and the board each at its own automatic poses: 0.5 mm
  // (seed 1, 14 poses: the marker 0.37-0.41 mm, the board 0.12 mm with the bent edges' tangents
  // and 0.18-0.31 mm before them; before the other fixes ~1 mm and 0.14-0.81 mm; every target
  // at seeds 1-3 in docs/registration.md, "Targets").
  EXPECT_LT(m.left_mm, 0.5);
  EXPECT_LT(m.right_mm, 0.5);
  EXPECT_LT(a.left_mm, 0.5);
  EXPECT_LT(a.right_mm, 0.5);
  EXPECT_LT(a.left_deg, 0.05);
  EXPECT_LT(a.right_deg, 0.05);
}

TEST_F(RegistrationTargetCaptureTest, TheRigFileRefusesABadTarget) {
  std::ifstream in(board_rig);
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  yaml.replace(yaml.find(board_spec()), board_spec().size(), "charuco:4x4:0.05:0.06:4x4_50");
  const std::string bad = (dir / "bad_rig.yaml").string();
  std::ofstream(bad) << yaml;
  auto loaded = sim::load_stereo_rig(bad);
  ASSERT_FALSE(loaded);
  EXPECT_THAT(loaded.error().message,
              HasSubstr("target: target 'charuco:4x4:0.05:0.06:4x4_50': marker side 0.06 m must be "
                        "smaller than the square side 0.05 m"));
}

}  // namespace
}  // namespace telear::session
