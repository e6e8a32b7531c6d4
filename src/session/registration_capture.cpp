#include "telear/session/registration_capture.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <thread>

#include "telear/core/angles.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/core/yaml_reader.hpp"
#include "telear/session/capture_session.hpp"
#include "telear/session/marker_visibility.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/capture_observations.hpp"
#include "telear/vision/hand_eye_registration.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::session {
namespace {

constexpr double kArmRangeRad = 0.6;    // the first three joints' spread around the start
constexpr double kWristRangeRad = 0.8;  // the others'
constexpr int kRoughCameraFrames = 5;   // frames tried for the target at the start pose

using Clock = std::chrono::steady_clock;

double rotation_distance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return std::abs(Eigen::AngleAxisd(Eigen::Matrix3d(a.transpose() * b)).angle());
}

cv::Mat rgb_view(const core::Image& image) {
  return cv::Mat(image.height, image.width, CV_8UC3,
                 const_cast<std::uint8_t*>(image.pixels.data()));
}

// Sends the move as a plan and waits for rest near `target`; the measured state at rest.
Result<net::RobotStateSample> move_to(const core::RobotModel& model, net::RobotClient& robot,
                                      const Eigen::VectorXd& target, const std::string& plan_id,
                                      const RegistrationCaptureOptions& options) {
  const auto state = robot.wait_state(0, 5.0);
  if (!state) return Error{"no robot state from the robot server within 5 s"};
  core::TrajectoryOptions timing;
  timing.velocity_scale = options.velocity_scale;
  timing.acceleration_scale = options.velocity_scale;
  auto trajectory = core::Trajectory::create(model, {{state->state.q}, {target}}, timing);
  if (!trajectory) return trajectory.error();
  if (auto ack = robot.execute_plan(plan_id, *trajectory); !ack) return ack.error();
  const auto start = Clock::now();
  std::uint64_t sequence = state->sequence;
  while (core::seconds_since(start) < options.pose_timeout_s) {
    const auto s = robot.wait_state(sequence, 1.0);
    if (!s) continue;
    sequence = s->sequence;
    if (s->state.estop) return Error{"the robot is e-stopped: " + s->state.estop_reason};
    if (s->state.mode == core::RobotMode::kIdle && s->state.trajectory_id.empty() &&
        (s->state.q - target).cwiseAbs().maxCoeff() <= options.rest_tolerance_rad) {
      std::this_thread::sleep_for(std::chrono::duration<double>(options.settle_s));
      const auto settled = robot.wait_state(sequence, 1.0);
      if (!settled) return Error{"no robot state after settling"};
      if (settled->state.mode != core::RobotMode::kIdle) {
        return Error{"the arm moved again while settling (mode " +
                     std::string(core::to_string(settled->state.mode)) + ")"};
      }
      return *settled;
    }
    if (s->last_trajectory_id == plan_id &&
        (s->last_trajectory_status == core::TrajectoryStatus::kCancelled ||
         s->last_trajectory_status == core::TrajectoryStatus::kAborted)) {
      return Error{"the move was " + std::string(core::to_string(s->last_trajectory_status))};
    }
  }
  return Error{"the arm did not come to rest at the pose within " +
               core::format_fixed(options.pose_timeout_s, 0) + " s"};
}

// Rough camera poses from the target at the current pose (auto poses): its pose in each camera
// (PnP on the points seen; a board may be seen in part) and its nominal pose on the flange.
Result<vision::StereoCameraModel> rough_cameras(const core::RobotModel& model,
                                                const net::RobotStateSample& state,
                                                const net::DecodedStereoFrame& frame,
                                                vision::StereoCameraModel cameras,
                                                const core::MarkerMount& marker,
                                                const vision::RegistrationTarget& target) {
  core::KinematicsData data(model);
  core::forward_kinematics(model, data, state.state.q);
  const Eigen::Isometry3d T_base_target = data.T_base_link.back() * marker.T_flange_marker;
  const std::vector<Eigen::Vector3d> points = target.points();
  const core::Image left = net::rgb_of(frame, true), right = net::rgb_of(frame, false);
  for (auto [eye, camera, image] :
       {std::tuple{"left", &cameras.left, &left}, std::tuple{"right", &cameras.right, &right}}) {
    const vision::TargetDetection seen =
        vision::detect_registration_target(rgb_view(*image), target);
    std::vector<vision::TargetPixel> pixels;
    for (std::size_t k = 0; k < seen.ids.size(); ++k)
      pixels.push_back({seen.ids[k], seen.pixels[k]});
    const auto T_cam_target = vision::target_pose_in_camera(*camera, points, pixels);
    if (!T_cam_target) {
      return Error{"the " + target.description() + " is not seen by the " + eye +
                   " camera at the arm's current pose: jog the arm until both cameras see "
                   "it, then capture again"};
    }
    camera->T_cam_base = *T_cam_target * T_base_target.inverse();
  }
  return cameras;
}

// Why the target at an automatic pose gives the registration nothing or little (empty: both
// eyes see it whole enough): the first frame's detection in each eye, as `telear register`
// will count it (a board: half its corners, vision::min_board_corners).
Result<std::string> unusable_view(const std::string& directory, const vision::CapturedFrame& frame,
                                  const vision::RegistrationTarget& target) {
  auto seen = vision::detect_in_captured_frame(directory, frame, target);
  if (!seen) return seen.error();
  const int corners = static_cast<int>(target.points().size());
  const int needed = target.is_board() ? vision::min_board_corners(target) : corners;
  std::string why;
  for (auto [eye, detection] : {std::pair{"left", &(*seen)[0]}, {"right", &(*seen)[1]}}) {
    const int found = static_cast<int>(detection->ids.size());
    if (found >= needed) continue;
    if (!why.empty()) why += ", ";
    why += std::string("the ") + eye + " eye " +
           (found == 0 ? "did not find it"
                       : "found " + std::to_string(found) + " of its " + std::to_string(corners) +
                             " corners (" + std::to_string(needed) + " needed)");
  }
  return why;
}

}  // namespace

Status RegistrationCaptureOptions::validate() const {
  auto bad = [](const std::string& what) { return Error{"capture: " + what}; };
  if (directory.empty()) return bad("directory: give the folder to write");
  if (auto_poses == 0 && poses.empty()) return bad("no poses: give auto:N or a poses file");
  if (auto_poses < 0 || auto_poses > 200)
    return bad("auto:" + std::to_string(auto_poses) + ": the number of poses must be 1..200");
  if (frames_per_pose < 1 || frames_per_pose > 30)
    return bad("frames_per_pose " + std::to_string(frames_per_pose) + " must be 1..30");
  if (!(velocity_scale > 0.0 && velocity_scale <= 1.0))
    return bad("velocity_scale " + core::format_number(velocity_scale) + " must be in (0, 1]");
  if (!(settle_s >= 0.0 && settle_s <= 10.0))
    return bad("settle_s " + core::format_number(settle_s) + " must be 0..10 s");
  if (!(rest_tolerance_rad > 0.0)) return bad("the rest tolerance must be positive");
  if (!(pose_timeout_s > 0.0)) return bad("the pose timeout must be positive");
  if (!(lease_heartbeat_s >= 0.0 && lease_heartbeat_s <= 10.0))
    return bad("the lease heartbeat must be 0..10 s");
  return {};
}

Result<std::vector<Eigen::VectorXd>> load_capture_poses_file(const std::string& path, int dof) {
  const std::string where = "poses file '" + path + "'";
  auto root = core::load_yaml_file(path, where);
  if (!root) return root.error();
  const YAML::Node poses = (*root)["poses"];
  if (!poses || !poses.IsSequence() || poses.size() == 0) {
    return Error{where + ": expected 'poses: [[q1, ..., qn], ...]' with at least one pose"};
  }
  std::vector<Eigen::VectorXd> out;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::string what = where + ": poses[" + std::to_string(i) + "]";
    auto values = core::yaml_numbers(poses[i], what);
    if (!values) return values.error();
    if (static_cast<int>(values->size()) != dof) {
      return Error{what + ": " + std::to_string(values->size()) + " joint values, the robot has " +
                   std::to_string(dof)};
    }
    out.push_back(Eigen::Map<const Eigen::VectorXd>(values->data(), dof));
  }
  return out;
}

std::vector<Eigen::VectorXd> choose_capture_poses(
    const core::RobotModel& model, const Eigen::VectorXd& q_start,
    const vision::StereoCameraModel& rough, const core::MarkerMount& marker, int count,
    std::uint64_t seed, const core::ArmBody* body, const core::Workspace* workspace,
    const std::optional<vision::RegistrationTarget>& target, std::vector<Eigen::VectorXd>* spares) {
  struct Candidate {
    Eigen::VectorXd q;
    Eigen::Isometry3d T_base_marker;
  };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MarkerVisibility visibility(model, marker, body, workspace, {}, target);
  const auto marker_at = [&](const Eigen::VectorXd& q) { return visibility.marker_pose(q); };
  std::vector<Candidate> candidates;
  const int tries = std::min(20000, 80 * count);
  for (int t = 0; t < tries; ++t) {
    Eigen::VectorXd q = q_start;
    for (int j = 0; j < model.dof(); ++j) {
      q[j] += unit(rng) * (j < 3 ? kArmRangeRad : kWristRangeRad);
      const double lo = model.lower_limits()[j], hi = model.upper_limits()[j];
      if (std::isfinite(lo) && std::isfinite(hi)) q[j] = std::clamp(q[j], lo + 0.01, hi - 0.01);
    }
    if (visibility.visible(rough.left, q) && visibility.visible(rough.right, q)) {
      candidates.push_back({q, marker_at(q)});
    }
  }
  // Farthest-point sampling: rotation angle plus position (2 rad per metre), from the start.
  std::vector<Eigen::Isometry3d> chosen_poses = {marker_at(q_start)};
  std::vector<Eigen::VectorXd> chosen;
  std::vector<double> nearest(candidates.size(), std::numeric_limits<double>::infinity());
  const int wanted = spares ? 2 * count : count;
  while (static_cast<int>(chosen.size()) < wanted && !candidates.empty()) {
    const Eigen::Isometry3d& last = chosen_poses.back();
    std::size_t best = 0;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const Eigen::Isometry3d& T = candidates[c].T_base_marker;
      const double d = rotation_distance(last.linear(), T.linear()) +
                       2.0 * (last.translation() - T.translation()).norm();
      nearest[c] = std::min(nearest[c], d);
      if (nearest[c] > nearest[best]) best = c;
    }
    if (!(nearest[best] > 0.0)) break;
    chosen.push_back(candidates[best].q);
    chosen_poses.push_back(candidates[best].T_base_marker);
    nearest[best] = 0.0;
  }
  // The spares: the next farthest, in that order.
  if (spares) {
    const std::size_t kept = std::min(chosen.size(), static_cast<std::size_t>(count));
    spares->assign(chosen.begin() + static_cast<std::ptrdiff_t>(kept), chosen.end());
    chosen.resize(kept);
  }
  // Visit them in nearest-neighbour order from the start.
  std::vector<Eigen::VectorXd> ordered;
  Eigen::VectorXd at = q_start;
  while (!chosen.empty()) {
    auto next = std::min_element(chosen.begin(), chosen.end(), [&](const auto& a, const auto& b) {
      return (a - at).norm() < (b - at).norm();
    });
    at = *next;
    ordered.push_back(*next);
    chosen.erase(next);
  }
  return ordered;
}

// The move to the finishing pose. A straight move from the last pose may sweep a link through
// another where the one from the start does not (the demo chooses its start so): refused, the
// arm goes back the way it came and tries again from each pose on the way.
Status finish_capture(const core::RobotModel& model, net::RobotClient& robot,
                      const Eigen::VectorXd& finish, const std::vector<Eigen::VectorXd>& reached,
                      const RegistrationCaptureOptions& options) {
  auto plan_id = [](const std::string& what) {
    return "capture-" + std::to_string(core::monotonic_ns()) + "-" + what;
  };
  auto direct = move_to(model, robot, finish, plan_id("finish"), options);
  if (direct) return Status::Ok();
  std::string last_refusal = direct.error().message;
  for (std::size_t k = reached.size(); k-- > 1;) {
    if (auto back = move_to(model, robot, reached[k - 1], plan_id("back"), options); !back) {
      return Error{"capture: the move to the finishing pose failed: " + last_refusal +
                   "; going back the way the arm came failed too: " + back.error().message};
    }
    auto again = move_to(model, robot, finish, plan_id("finish"), options);
    if (again) return Status::Ok();
    last_refusal = again.error().message;
  }
  return Error{"capture: the move to the finishing pose failed: " + last_refusal};
}

Result<RegistrationCaptureResult> capture_for_registration(
    const core::RobotModel& model, net::RobotClient& robot, net::VisionClient& vision,
    const RegistrationCaptureOptions& options,
    const std::function<void(const CaptureProgress&)>& progress) {
  if (Status s = options.validate(); !s) return s.error();
  auto info = open_capture_folder(vision, options.directory);
  if (!info) return info.error();

  RegistrationCaptureResult out;
  out.cameras = info->cameras;
  out.capture.robot = model.name();
  const vision::RegistrationTarget target =
      options.target ? *options.target : vision::registration_target_from_mount(options.marker);
  out.capture.target = target.spec();
  std::vector<Eigen::VectorXd> poses = options.poses;
  // Auto poses: where to go instead of a pose whose frames show the target too little (hidden
  // by what the rough cameras and the nominal body did not foresee, or its cells too small to
  // decode there).
  std::vector<Eigen::VectorXd> spares;
  if (options.auto_poses > 0) {
    const auto state = robot.wait_state(0, 5.0);
    if (!state) return Error{"capture: no robot state from the robot server within 5 s"};
    // Up to five frames: a small board's markers (cells of ~2 px) decode in one frame and not
    // in the next, with the sensor's noise (issue 26 item 1: a start the operator had seen the
    // board at was refused).
    std::uint64_t last_id = 0;
    Result<vision::StereoCameraModel> rough = Error{"no frame"};
    for (int attempt = 0; attempt < kRoughCameraFrames; ++attempt) {
      const auto frame = frame_after(vision, core::monotonic_ns(), last_id, 5.0);
      if (!frame) return Error{"capture: no video frame from the vision server within 5 s"};
      last_id = frame->frame_id;
      rough = rough_cameras(model, *state, *frame, info->cameras, options.marker, target);
      if (rough) break;
    }
    if (!rough) return Error{"capture: " + rough.error().message};
    std::optional<core::ArmBody> body = options.body;
    if (!body) {
      auto description = core::body_description_for(model);
      if (!description) return Error{"capture: the arm's body: " + description.error().message};
      body = core::build_arm_body(*description);
    }
    poses = choose_capture_poses(
        model, state->state.q, *rough, options.marker, options.auto_poses, options.seed, &*body,
        options.workspace ? &*options.workspace : nullptr, target, &spares);
    if (poses.empty()) {
      return Error{
          "capture: no pose around the current one keeps the " + target.description() +
          " in both cameras' view: move the arm so it faces both cameras, then capture again"};
    }
    if (static_cast<int>(poses.size()) < options.auto_poses) {
      out.notes.push_back("only " + std::to_string(poses.size()) + " of " +
                          std::to_string(options.auto_poses) + " automatic poses keep the " +
                          target.description() + " in view");
    }
  }

  // The lease only now: choosing the automatic poses (thousands of sight-line tests) keeps a
  // 2-core machine busy long enough to starve a 250 ms heartbeat that is not needed yet.
  const bool lease_was_held = robot.lease_held();
  if (!lease_was_held) {
    if (Status s = robot.acquire_lease(options.lease_heartbeat_s); !s)
      return Error{"capture: lease: " + s.error().message};
  }
  struct ReleaseLease {
    net::RobotClient& robot;
    bool release;
    ~ReleaseLease() {
      if (release) (void)robot.release_lease();
    }
  } release{robot, !lease_was_held};
  std::uint64_t last_frame_id = 0;
  // The poses the arm reached, from where it started: each move between two of them was
  // accepted, so the way back along them is too (the server checks a straight move the same
  // way in both directions).
  std::vector<Eigen::VectorXd> reached;
  if (const auto state = robot.wait_state(0, 5.0)) reached.push_back(state->state.q);
  for (int p = 0; p < static_cast<int>(poses.size()); ++p) {
    const int count = static_cast<int>(poses.size());
    CaptureProgress report{p + 1, count, false, ""};
    const std::string label = "pose " + std::to_string(p + 1) + "/" + std::to_string(count);
    const std::string plan_id =
        "capture-" + std::to_string(core::monotonic_ns()) + "-" + std::to_string(p);
    auto rest = move_to(model, robot, poses[static_cast<std::size_t>(p)], plan_id, options);
    if (!rest) {
      report.message = label + " skipped: " + rest.error().message;
      out.notes.push_back(report.message);
      if (progress) progress(report);
      continue;
    }
    reached.push_back(poses[static_cast<std::size_t>(p)]);
    const int index = static_cast<int>(out.capture.poses.size());
    vision::CapturedPose pose;
    pose.q_commanded = poses[static_cast<std::size_t>(p)];
    pose.q = rest->state.q;
    pose.joint_time_ns = rest->capture_ns;
    PoseFramesOptions frames_options;
    frames_options.frames = options.frames_per_pose;
    frames_options.max_sync_skew_ns = options.max_sync_skew_ns;
    frames_options.timeout_s = options.pose_timeout_s;
    auto frames =
        capture_pose_frames(vision, options.directory, index, *rest, frames_options, last_frame_id);
    if (!frames) return frames.error();
    pose.frames = std::move(*frames);
    if (pose.frames.empty()) {
      report.message = label + " skipped: no synchronized stereo frame after the arm settled";
      out.notes.push_back(report.message);
      if (progress) progress(report);
      continue;
    }
    if (options.auto_poses > 0) {
      auto unusable = unusable_view(options.directory, pose.frames.front(), target);
      if (!unusable) return Error{"capture: " + unusable.error().message};
      if (!unusable->empty()) {
        // Not kept: its frames go, and the next spare pose takes its place (when none is left,
        // the capture has one pose fewer: a pose without the target adds nothing).
        for (const vision::CapturedFrame& frame : pose.frames) {
          std::error_code ignored;
          std::filesystem::remove(std::filesystem::path(options.directory) / frame.left_image,
                                  ignored);
          std::filesystem::remove(std::filesystem::path(options.directory) / frame.right_image,
                                  ignored);
          // Its folder too (empty now; the next pose kept, of the same index, makes it again).
          std::filesystem::remove(
              (std::filesystem::path(options.directory) / frame.left_image).parent_path(), ignored);
        }
        report.message =
            label +
            (spares.empty() ? " dropped (no spare pose left): " : " replaced by another pose: ") +
            *unusable;
        out.notes.push_back(report.message);
        if (progress) progress(report);
        if (!spares.empty()) {
          poses.push_back(spares.front());
          spares.erase(spares.begin());
        }
        continue;
      }
    }
    out.capture.poses.push_back(std::move(pose));
    report.captured = true;
    report.message =
        label + ": " + std::to_string(out.capture.poses.back().frames.size()) + " frames";
    if (progress) progress(report);
  }
  if (options.finish_pose) {
    if (Status s = finish_capture(model, robot, *options.finish_pose, reached, options); !s) {
      return s.error();
    }
  }
  if (out.capture.poses.empty()) {
    return Error{"capture: no pose was captured (" +
                 (out.notes.empty() ? std::string("no poses") : out.notes.back()) + ")"};
  }
  if (Status s = write_capture_cameras(options.directory, *info, out.capture); !s) return s.error();
  if (Status s = vision::write_capture_manifest(out.capture, options.directory); !s) {
    return Error{"capture: " + s.error().message};
  }
  return out;
}

}  // namespace telear::session
