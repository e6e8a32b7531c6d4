// The library modules the commands call (issue 11: apps only parse options, call libraries and
// print): what `telear kin`, `render`, `eval`, `register`, `calibrate` and `plan check` used
// to compute in apps/, tested here without a process: values from the command line, the IK
// listing, the reports' text and JSON, the snapshot's view and input checks, the one printf
// formatter and the one YAML reader.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "telear/core/angles.hpp"
#include "telear/core/ik_listing.hpp"
#include "telear/core/joint_values.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/kinematics_report.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/pose_text.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/geometry/allowed_collisions.hpp"
#include "telear/lab/simulated_robot_server.hpp"
#include "telear/lab/vision_source.hpp"
#include "telear/render/arm_snapshot.hpp"
#include "telear/session/plan_check_report.hpp"
#include "telear/vision/accuracy_check.hpp"
#include "telear/vision/image_calibration.hpp"
#include "telear/vision/registration.hpp"
#include "test_util/test_util.hpp"

namespace telear {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// [SECTION] core: joint values, poses as text

TEST(JointValues, ANameOrOneNumberPerJointInRadiansOrDegrees) {
  const auto model = test::puma560();
  auto named = core::parse_joint_values(*model, "qn", "--q", true);
  ASSERT_TRUE(named) << named.error().message;
  EXPECT_EQ(*named, *model->named_configuration("qn"));  // a name is taken as is, not converted
  auto degrees = core::parse_joint_values(*model, "0,90,-45,0,0,180", "--q", true);
  ASSERT_TRUE(degrees) << degrees.error().message;
  EXPECT_DOUBLE_EQ((*degrees)[1], std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ((*degrees)[5], std::numbers::pi);
  auto radians = core::parse_joint_values(*model, "0,1.5,0,0,0,0", "--q", false);
  ASSERT_TRUE(radians);
  EXPECT_EQ((*radians)[1], 1.5);
  EXPECT_EQ(core::parse_joint_values(*model, "0,0,0", "--q", false).error().message,
            "--q: expected 6 numbers, got 3 (robot 'puma560' has 6 joints)");
  EXPECT_EQ(core::parse_joint_values(*model, "0,x,0,0,0,0", "--initial", false).error().message,
            "--initial: item 2 ('x') is not a number (robot 'puma560' has 6 joints)");
}

TEST(JointValues, DegreesRoundTripAndTheFixedWidthRow) {
  const auto model = test::puma560();
  Eigen::VectorXd q(6);
  q << 0.1, -0.2, 0.3, -0.4, 0.5, -0.6;
  const Eigen::VectorXd back =
      core::joint_values_from_degrees(*model, core::joint_values_to_degrees(*model, q));
  EXPECT_LT((back - q).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_NEAR(core::joint_values_to_degrees(*model, q)[0], 5.729577951308232, 1e-12);
  Eigen::VectorXd row(3);
  row << -0.001, 2.5, -12.345;
  // No "-0.00" for a value that rounds to zero.
  EXPECT_EQ(core::format_joint_values(row, 7, 2), "[   0.00,    2.50,  -12.35]");
}

TEST(PoseText, SixteenNumbersCommaOrBlankSeparated) {
  auto commas = core::rigid_transform_from_text("1,0,0,0.5, 0,1,0,0.1, 0,0,1,0.4, 0,0,0,1", "--T");
  ASSERT_TRUE(commas) << commas.error().message;
  EXPECT_TRUE(commas->translation().isApprox(Eigen::Vector3d(0.5, 0.1, 0.4)));
  auto blanks = core::rigid_transform_from_text("1 0 0 0.5\n0 1 0 0.1\n0 0 1 0.4\n0 0 0 1", "--T");
  ASSERT_TRUE(blanks) << blanks.error().message;
  EXPECT_TRUE(blanks->isApprox(*commas));
  // A printed rotation (a few digits) is accepted and re-orthonormalized.
  auto printed = core::rigid_transform_from_text(
      "0.70711,-0.70711,0,0, 0.70711,0.70711,0,0, 0,0,1,0, 0,0,0,1", "--T");
  ASSERT_TRUE(printed) << printed.error().message;
  EXPECT_NEAR(printed->linear().determinant(), 1.0, 1e-12);
  EXPECT_EQ(core::rigid_transform_from_text("1,0,0", "--T").error().message,
            "--T: expected 16 numbers, got 3");
  EXPECT_THAT(
      core::rigid_transform_from_text("1,0,0,0,0,2,0,0,0,0,1,0,0,0,0,1", "--T").error().message,
      StartsWith("--T is not a rigid transform: "));
}

TEST(PoseText, XyzAndRollPitchYawInRadiansOrDegrees) {
  auto pose = core::pose_from_text("0.5,0.1,0.4,0,90,0", "--pose", true);
  ASSERT_TRUE(pose) << pose.error().message;
  const Eigen::Isometry3d expected = core::pose_from_xyz_rpy(
      {0.5, 0.1, 0.4}, Eigen::Vector3d(0, core::radians_from_degrees(90), 0));
  EXPECT_TRUE(pose->isApprox(expected, 1e-15));
  EXPECT_EQ(core::pose_from_text("0.5,0.1", "--pose", false).error().message,
            "--pose: expected 6 numbers, got 2 (x,y,z in m, roll,pitch,yaw in rad)");
  EXPECT_EQ(core::pose_from_text("0.5,0.1", "--pose", true).error().message,
            "--pose: expected 6 numbers, got 2 (x,y,z in m, roll,pitch,yaw in deg)");
}

// [SECTION] core: the IK listing and the kin reports

TEST(IkListing, ThePumaGetsItsEightClosedFormSolutionsEachBackOnThePose) {
  const auto model = test::puma560();
  const Eigen::Isometry3d T = core::tool_pose(*model, *model->named_configuration("qn"));
  auto listing = core::list_ik_solutions(*model, T);
  ASSERT_TRUE(listing) << listing.error().message;
  EXPECT_TRUE(listing->closed_form);
  ASSERT_EQ(listing->result.solutions.size(), 8u);
  for (const core::IkSolution& s : listing->result.solutions) {
    EXPECT_LT(test::max_abs_diff(core::tool_pose(*model, s.q).matrix(), T.matrix()), 1e-9)
        << s.config;
  }
  auto one = core::list_ik_solutions(*model, T, "lun");
  ASSERT_TRUE(one);
  ASSERT_EQ(one->result.solutions.size(), 1u);
  EXPECT_EQ(one->result.solutions[0].config, "lun");
  Eigen::Isometry3d far = T;
  far.translation() = Eigen::Vector3d(5.0, 0.0, 0.0);
  EXPECT_FALSE(core::list_ik_solutions(*model, far));
}

TEST(IkListing, AnArmWithoutTheClosedFormListsNumericSolutionsAndRefusesAConfig) {
  auto model = core::load_robot("arm7");
  ASSERT_TRUE(model) << model.error().message;
  Eigen::VectorXd q = Eigen::VectorXd::Zero((*model)->dof());
  q[1] = 0.4;
  q[3] = -1.0;
  const Eigen::Isometry3d T = core::tool_pose(**model, q);
  auto listing = core::list_ik_solutions(**model, T);
  ASSERT_TRUE(listing) << listing.error().message;
  EXPECT_FALSE(listing->closed_form);
  ASSERT_EQ(listing->result.solutions.size(), 1u);  // a redundant arm: the nearest one
  EXPECT_LT(test::max_abs_diff(core::tool_pose(**model, listing->result.solutions[0].q).matrix(),
                               T.matrix()),
            1e-9);
  EXPECT_THAT(core::list_ik_solutions(**model, T, "lun").error().message,
              StartsWith("config selects closed-form solutions, and "));
}

TEST(KinematicsReport, ThePoseLineTheTablesAndTheJson) {
  const auto model = test::puma560();
  const Eigen::Isometry3d T =
      core::pose_from_xyz_rpy({0.45, -0.15, 0.43}, Eigen::Vector3d(core::radians_from_degrees(10),
                                                                   core::radians_from_degrees(-20),
                                                                   core::radians_from_degrees(30)));
  EXPECT_EQ(core::pose_line(T),
            "  xyz = (0.4500, -0.1500, 0.4300) m   rpy = (10.000, -20.000, 30.000) deg\n");
  const std::string info = core::robot_info_text(*model);
  EXPECT_THAT(info, StartsWith("puma560: 6 joints, from "));
  EXPECT_THAT(info, HasSubstr("  #   joint          type                     limits        max vel "
                              "         max acc\n"));
  EXPECT_THAT(info, HasSubstr("named configurations (deg):\n"));
  const nlohmann::json j = nlohmann::json::parse(core::robot_info_json(*model));
  EXPECT_EQ(j["dof"], 6);
  EXPECT_EQ(j["joints"].size(), 6u);

  const Eigen::VectorXd qz = *model->named_configuration("qz");
  const nlohmann::json fk = nlohmann::json::parse(core::forward_kinematics_json(*model, qz));
  EXPECT_TRUE(fk["within_limits"].get<bool>());
  EXPECT_EQ(fk["T_base_tool"].size(), 4u);
  EXPECT_THAT(core::forward_kinematics_text(*model, qz), StartsWith("T_base_tool:\n  ["));

  auto listing = core::list_ik_solutions(*model, core::tool_pose(*model, qz), "lun");
  ASSERT_TRUE(listing);
  const nlohmann::json ik = nlohmann::json::parse(core::ik_listing_json(*model, *listing, true));
  EXPECT_EQ(ik["method"], "analytic");
  EXPECT_EQ(ik["units"], "deg");
  EXPECT_THAT(core::ik_listing_text(*model, core::tool_pose(*model, qz), *listing, false),
              StartsWith("puma560: 1 solution (closed form) for\n"));
  EXPECT_THAT(core::kinematics_tour_text(*model), HasSubstr("worst round trip |FK(IK(T)) - T| = "));
}

// [SECTION] core: the one printf formatter

TEST(FormatValues, SeveralValuesInOneFormatNeverTruncated) {
  EXPECT_EQ(core::format_values("%.3f px (alone %.3f)", 0.1234, 2.0), "0.123 px (alone 2.000)");
  EXPECT_EQ(core::format_values("[%*zu/%zu] ", 2, std::size_t{3}, std::size_t{12}), "[ 3/12] ");
  const std::string long_text = core::format_values("%300.1f", 1.0);
  EXPECT_EQ(long_text.size(), 300u);
  EXPECT_EQ(long_text.substr(297), "1.0");
}

// [SECTION] render: the snapshot's view and input checks (no GL needed)

TEST(ArmSnapshot, TheWholeArmViewSeesTheArmAndItsStereoEyesAreSixCentimetresApart) {
  const auto model = test::puma560();
  const Eigen::VectorXd q = *model->named_configuration("qn");
  const auto mono = render::whole_arm_view(*model, q, 640, 480, false);
  ASSERT_EQ(mono.size(), 1u);
  EXPECT_EQ(mono[0].name, "");
  const auto tool = mono[0].camera.project(core::tool_pose(*model, q).translation());
  ASSERT_TRUE(tool);
  EXPECT_GT(tool->x(), 0.0);
  EXPECT_LT(tool->x(), 640.0);
  EXPECT_GT(tool->y(), 0.0);
  EXPECT_LT(tool->y(), 480.0);
  const auto stereo = render::whole_arm_view(*model, q, 640, 480, true);
  ASSERT_EQ(stereo.size(), 2u);
  EXPECT_EQ(stereo[0].name, "left");
  EXPECT_EQ(stereo[1].name, "right");
  const Eigen::Vector3d left = stereo[0].camera.T_cam_base.inverse().translation();
  const Eigen::Vector3d right = stereo[1].camera.T_cam_base.inverse().translation();
  EXPECT_NEAR((left - right).norm(), 0.06, 1e-12);
}

TEST(ArmSnapshot, InputsAreCheckedBeforeAnyGlWork) {
  const auto model = test::puma560();
  const Eigen::VectorXd q = *model->named_configuration("qn");
  const auto mono = render::whole_arm_view(*model, q, 64, 48, false);
  const auto stereo = render::whole_arm_view(*model, q, 64, 48, true);
  core::Image frame;
  frame.width = 32;
  frame.height = 24;
  EXPECT_TRUE(render::check_snapshot_inputs(stereo, {}, render::StereoLayout::kSideBySide));
  EXPECT_EQ(render::check_snapshot_inputs(mono, {frame}, render::StereoLayout::kSideBySide)
                .error()
                .message,
            "background image is 32x24 but the camera's image is 64x48");
  EXPECT_EQ(render::check_snapshot_inputs(mono, {frame, frame}, render::StereoLayout::kSideBySide)
                .error()
                .message,
            "background gives two images but only one eye is drawn");
  auto unequal = stereo;
  unequal[1].camera.width = 80;
  EXPECT_THAT(
      render::check_snapshot_inputs(unequal, {}, render::StereoLayout::kTopBottom).error().message,
      StartsWith("the left and right cameras have different image sizes"));
  EXPECT_TRUE(render::check_snapshot_inputs(unequal, {}, render::StereoLayout::kSeparate));
}

TEST(ArmSnapshot, TheEyesTheBackgroundsAndTheOutputNames) {
  const auto model = test::puma560();
  const Eigen::VectorXd q = *model->named_configuration("qn");
  auto right = render::snapshot_eyes("", "right", *model, q, 64, 48);
  ASSERT_TRUE(right) << right.error().message;
  ASSERT_EQ(right->size(), 1u);
  EXPECT_EQ((*right)[0].name, "right");
  auto both = render::snapshot_eyes("", "both", *model, q, 64, 48);
  ASSERT_TRUE(both);
  EXPECT_EQ(both->size(), 2u);
  EXPECT_EQ(render::snapshot_eyes("", "middle", *model, q, 64, 48).error().message,
            "eye must be left, right or both, got 'middle'");
  EXPECT_THAT(render::snapshot_eyes("/nonexistent.yaml", "", *model, q, 64, 48).error().message,
              HasSubstr("/nonexistent.yaml"));
  auto none = render::read_snapshot_backgrounds("");
  ASSERT_TRUE(none);
  EXPECT_TRUE(none->empty());
  EXPECT_EQ(render::read_snapshot_backgrounds(",b.png").error().message,
            "background: empty file name in ',b.png'");
  EXPECT_THAT(render::read_snapshot_backgrounds("/nonexistent.png").error().message,
              HasSubstr("/nonexistent.png"));
  EXPECT_EQ(render::snapshot_eye_path("out/view.png", "left"), "out/view_left.png");
  EXPECT_EQ(render::snapshot_eye_path("out.d/view", "right"), "out.d/view_right");
}

// [SECTION] vision: the eval and register tables, calibration from image files

TEST(AccuracyReportText, EveryFigureAndTheVerdict) {
  vision::AccuracyReport report;
  for (vision::EyeAccuracy* eye : {&report.left, &report.right}) {
    eye->truth = vision::look_at_camera(640, 480, 0.8, {1, 0, 1}, {0, 0, 0.5}, {0, 0, 1});
    eye->estimate = eye->truth;
    eye->estimate.fx *= 1.001;
    eye->registration = {0.25, 0.01};
    eye->overlay = {1200, 0.1, 0.3};
  }
  report.baseline_truth_m = 0.06;
  report.baseline_estimate_m = 0.0601;
  report.configurations = 60;
  report.samples_per_configuration = 20;
  const auto checks = vision::accuracy_checks(report);
  const std::string text = vision::accuracy_report_text(report, checks);
  EXPECT_THAT(text, HasSubstr("\nleft camera            truth       estimate      error\n"));
  EXPECT_THAT(text, HasSubstr("  fx             "));
  EXPECT_THAT(text, HasSubstr("   +0.1000 %\n"));
  EXPECT_THAT(text, HasSubstr("  registration      0.2500 mm    0.01000 deg\n"));
  EXPECT_THAT(text, HasSubstr("  overlay        RMS 0.1000 px  max 0.3000 px  (1200 point "
                              "projections)\n"));
  EXPECT_THAT(text, HasSubstr("\nbaseline         truth 60.0000 mm  estimate 60.1000 mm  error "
                              "+0.1000 mm\n"));
  EXPECT_THAT(text, HasSubstr("overlay: 60 arm configurations x 20 body points\n"));
  EXPECT_THAT(text, HasSubstr("\ntargets (issue 4 item 7)\n"));
  EXPECT_THAT(text, HasSubstr("overall: PASS\n"));
  report.right.overlay.max_px = 2.0;
  EXPECT_THAT(vision::accuracy_report_text(report, vision::accuracy_checks(report)),
              HasSubstr("overall: FAIL\n"));
}

TEST(RegistrationSummary, ResidualsBeforeAndAfterAndTheCameraCentres) {
  vision::RegistrationResult result;
  result.T_left_base.translation() << 0.02, 0.01, 1.0;  // the camera 1 m below the base origin
  result.T_right_base.translation() << -0.06, 0.0, 1.0;
  result.initial_left = {40, 1.5, 3.25};
  result.left = {40, 0.125, 0.5};
  result.iterations = 7;
  result.notes = {"configuration 3 set aside"};
  const std::string text = vision::registration_summary(result);
  EXPECT_THAT(text, StartsWith("  note: configuration 3 set aside\nresiduals after the PnP start:\n"
                               "  left                       40 points  RMS   1.5000 px  max   "
                               "3.2500 px\n"));
  EXPECT_THAT(text, HasSubstr("residuals after refinement (7 Levenberg-Marquardt iterations):\n"));
  EXPECT_THAT(text, HasSubstr("camera centres in the base frame (m): left [-0.0200, -0.0100, "
                              "-1.0000], right [0.0600, 0.0000, -1.0000]\n"));
}

TEST(ImageCalibration, NoImagesIsAnErrorBeforeAnyFit) {
  auto pattern = vision::parse_calibration_pattern("chessboard:9x6:0.025");
  ASSERT_TRUE(pattern);
  std::vector<std::string> stages;
  vision::ImageCalibrationProgress progress;
  progress.stage = [&stages](const std::string& s) { stages.push_back(s); };
  EXPECT_FALSE(vision::calibrate_image_files({}, {}, *pattern, {}, progress));
  ASSERT_EQ(stages.size(), 1u);
  EXPECT_EQ(stages[0], "detecting chessboard:9x6:0.025 in 0 images");
}

// [SECTION] session: the plan check's report

TEST(PlanCheckReport, TextAndJsonOfAContact) {
  geometry::TrajectoryCheckReport report;
  report.collisions.push_back({1.2345, "link6", "table_top", false, 0.0042, 2});
  report.min_clearance = {0.0, 1.2345, 2, "link6", "table_top", false};
  report.min_workspace_clearance = report.min_clearance;
  report.evaluations = 321;
  const std::string text = session::plan_check_text("p.yaml", 9, 6.12, "ws.yaml", report);
  EXPECT_EQ(text,
            "plan p.yaml (9 waypoints, 6.120 s) in ws.yaml: COLLISION\n"
            "  contact at 1.234 s (segment 2): link6 with table_top, depth 4.2 mm\n"
            "  min clearance to the workspace 0.0 mm at 1.234 s: link6 to table_top\n");
  const nlohmann::json j = nlohmann::json::parse(session::plan_check_json(report, 6.12));
  EXPECT_FALSE(j["collision_free"].get<bool>());
  EXPECT_EQ(j["collisions"][0]["link"], "link6");
  EXPECT_EQ(j["min_clearance_m"], 0.0);
  EXPECT_EQ(j["min_workspace_clearance"]["distance_m"], 0.0);
  EXPECT_EQ(j["configurations_checked"], 321);
  EXPECT_EQ(j["duration_s"], 6.12);
  // Nothing measured: null.
  const nlohmann::json none =
      nlohmann::json::parse(session::plan_check_json(geometry::TrajectoryCheckReport{}, 0.0));
  EXPECT_TRUE(none["min_clearance_m"].is_null());
  EXPECT_TRUE(none["min_workspace_clearance"]["distance_m"].is_null());
}

// Issue 26: the arm's own nearest pair (the PUMA's wrist housings, 2.0 mm apart by design) is
// not the clearance an operator acts on: min_clearance_m is the workspace's, as the demo
// report's and the safety margin's; the arm's pair is still named, after it.
TEST(PlanCheckReport, TheMinimumClearanceIsTheWorkspacesNotTheArmsOwn) {
  geometry::TrajectoryCheckReport report;
  report.min_clearance = {0.002, 0.099, 0, "link4", "link6", true};
  report.min_workspace_clearance = {1.025, 0.0, 0, "link4", "crate", false};
  const nlohmann::json j = nlohmann::json::parse(session::plan_check_json(report, 0.38));
  EXPECT_EQ(j["min_clearance_m"], 1.025);
  EXPECT_EQ(j["min_workspace_clearance"]["object"], "crate");
  EXPECT_EQ(j["min_clearance"]["object"], "link6");  // over every pair, the arm's own included
  EXPECT_EQ(session::plan_check_text("p.yaml", 2, 0.38, "ws.yaml", report),
            "plan p.yaml (2 waypoints, 0.380 s) in ws.yaml: collision-free\n"
            "  min clearance to the workspace 1025.0 mm at 0.000 s: link4 to crate\n"
            "  nearest of the arm's own links 2.0 mm at 0.099 s: link4 to link link6\n");
}

// [SECTION] session: the vision server's source, chosen by name

TEST(VisionSource, EachKindOpensOrSaysWhatIsWrong) {
  lab::VisionSourceOptions synthetic;
  synthetic.kind = "synthetic";
  synthetic.size = core::ImageSize{64, 48};
  auto opened = lab::open_vision_source(synthetic);
  ASSERT_TRUE(opened) << opened.error().message;
  ASSERT_TRUE(opened->source);
  EXPECT_FALSE(opened->robot);
  EXPECT_TRUE(opened->warnings.empty());

  lab::VisionSourceOptions sim;  // the shipped rig; its size is the rig file's
  sim.size = core::ImageSize{64, 48};
  auto rig = lab::open_vision_source(sim);
  ASSERT_TRUE(rig) << rig.error().message;
  ASSERT_EQ(rig->warnings.size(), 1u);
  EXPECT_THAT(rig->warnings[0], StartsWith("the size is ignored for the sim source"));

  lab::VisionSourceOptions bad;
  bad.kind = "bogus";
  EXPECT_EQ(lab::open_vision_source(bad).error().message,
            "source 'bogus' is not one of sim, files, v4l2, synthetic");
  bad.kind = "files";
  EXPECT_EQ(lab::open_vision_source(bad).error().message,
            "the files source needs a left and a right file");
  bad.robot_server = "127.0.0.1:1";
  EXPECT_EQ(lab::open_vision_source(bad).error().message,
            "robot_server is for the sim source (the simulated rig follows the robot)");
}

// [SECTION] session: telear robot-server's server

TEST(SimulatedRobotServer, StartsOnAnEphemeralPortOrSaysWhyNot) {
  auto description = core::load_robot_description({"puma560", "", {}});
  ASSERT_TRUE(description) << description.error().message;
  lab::SimulatedRobotServerOptions options;
  options.server.listen_address = "127.0.0.1:0";
  options.server.token = "t";
  options.heartbeat_ns = 5'000'000'000;  // beyond the default bounds: they are widened
  options.initial_q = *description->model->named_configuration("qr");
  auto server = lab::start_simulated_robot_server(*description, options);
  ASSERT_TRUE(server) << server.error().message;
  EXPECT_THAT((*server)->address(), StartsWith("127.0.0.1:"));
  EXPECT_NE((*server)->address(), "127.0.0.1:0");
  (*server)->shutdown();

  options.initial_q[2] = 3.0;  // beyond the elbow's limit
  EXPECT_THAT(lab::start_simulated_robot_server(*description, options).error().message,
              HasSubstr("joint 3"));
  options.initial_q = *description->model->named_configuration("qr");
  options.check_collisions = true;
  options.server.workspace_file = "/nonexistent/ws.yaml";
  EXPECT_THAT(lab::start_simulated_robot_server(*description, options).error().message,
              HasSubstr("/nonexistent/ws.yaml"));
}

// [SECTION] geometry: the allowed-collision block is read through core's YAML reader

TEST(AllowedCollisionsYaml, ASyntaxErrorNamesTheSourceAndTheLine) {
  auto m = geometry::AllowedCollisionMatrix::from_yaml("- [a, b]\n- [c, d", "robot.yaml");
  ASSERT_FALSE(m);
  EXPECT_THAT(m.error().message, StartsWith("robot.yaml: not valid YAML at line "));
  auto ok = geometry::AllowedCollisionMatrix::from_yaml("- [b, a, adjacent]\n", "robot.yaml");
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_TRUE(ok->allowed("a", "b"));
}

}  // namespace
}  // namespace telear
