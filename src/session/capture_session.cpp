#include "telear/session/capture_session.hpp"

#include <chrono>
#include <filesystem>
#include <future>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "telear/core/clock.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/number_format.hpp"
#include "telear/vision/calibration_file.hpp"

namespace telear::session {
namespace {

constexpr double kPoll = 0.01;  // s

using Clock = std::chrono::steady_clock;

cv::Mat bgr_of(const core::Image& image) {
  const cv::Mat rgb(image.height, image.width, CV_8UC3,
                    const_cast<std::uint8_t*>(image.pixels.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

// "pose 0: ..." (detect_capture_targets names the one pose it was given) as "pose N: ...".
std::string renamed(const std::string& note, int index) {
  const std::string prefix = "pose 0";
  if (note.rfind(prefix, 0) != 0) return note;
  return "pose " + std::to_string(index) + note.substr(prefix.size());
}

}  // namespace

// [SECTION] shared with capture_for_registration

Result<net::CameraInfoReply> open_capture_folder(net::VisionClient& vision,
                                                 const std::string& directory) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) return Error{"capture: cannot create '" + directory + "': " + ec.message()};
  if (fs::exists(fs::path(directory) / "capture.yaml")) {
    return Error{"capture: '" + directory +
                 "' already holds a capture (capture.yaml): give a new folder"};
  }
  // The client connects lazily: a first call may meet a server still starting or a loaded
  // machine, so it is tried three times before giving up.
  auto info = vision.get_camera_info();
  for (int attempt = 1; !info && attempt < 3; ++attempt) {
    std::this_thread::sleep_for(std::chrono::seconds(1));
    info = vision.get_camera_info();
  }
  if (!info) return Error{"capture: camera info: " + info.error().message};
  if (!info->found) {
    return Error{
        "capture: the vision server has no camera calibration (start it with a "
        "calibration file): registration needs the intrinsics"};
  }
  return *info;
}

Status write_capture_cameras(const std::string& directory, const net::CameraInfoReply& info,
                             vision::CaptureSet& capture) {
  // The calibration the poses were captured with, so `register --captures DIR` needs no --rig.
  if (info.calibration_yaml.empty()) return Status::Ok();
  const std::string path = (std::filesystem::path(directory) / "cameras.yaml").string();
  if (Status s = vision::write_files_atomically({{path, info.calibration_yaml}}); !s) {
    return Error{"capture: " + s.error().message};
  }
  capture.camera_file = "cameras.yaml";
  return Status::Ok();
}

std::shared_ptr<const net::DecodedStereoFrame> frame_after(net::VisionClient& vision,
                                                           std::int64_t after_ns,
                                                           std::uint64_t after_id,
                                                           double timeout_s) {
  const auto start = Clock::now();
  while (core::seconds_since(start) < timeout_s) {
    if (auto frame = vision.latest_frame()) {
      const auto& f = **frame;
      if (f.frame_id > after_id && std::min(f.capture_ns_left, f.capture_ns_right) > after_ns) {
        return *frame;
      }
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(kPoll));
  }
  return nullptr;
}

Result<std::vector<vision::CapturedFrame>> capture_pose_frames(net::VisionClient& vision,
                                                               const std::string& directory,
                                                               int index,
                                                               const net::RobotStateSample& rest,
                                                               const PoseFramesOptions& options,
                                                               std::uint64_t& last_frame_id) {
  std::vector<vision::CapturedFrame> frames;
  const std::int64_t rest_ns = rest.capture_client_ns();
  const auto start = Clock::now();
  while (static_cast<int>(frames.size()) < options.frames &&
         core::seconds_since(start) < options.timeout_s) {
    const auto frame = frame_after(vision, rest_ns, last_frame_id, 2.0);
    if (!frame) continue;
    last_frame_id = frame->frame_id;
    if (std::abs(frame->capture_ns_left - frame->capture_ns_right) > options.max_sync_skew_ns) {
      continue;  // not one stereo exposure
    }
    vision::CapturedFrame captured;
    captured.frame_id = frame->frame_id;
    captured.left_time_ns = frame->capture_ns_left;
    captured.right_time_ns = frame->capture_ns_right;
    const int f = static_cast<int>(frames.size());
    captured.left_image = vision::captured_image_path(index, f, true);
    captured.right_image = vision::captured_image_path(index, f, false);
    if (Status s =
            vision::write_captured_images(directory, captured, bgr_of(net::rgb_of(*frame, true)),
                                          bgr_of(net::rgb_of(*frame, false)));
        !s) {
      return Error{"capture: " + s.error().message};
    }
    frames.push_back(captured);
  }
  return frames;
}

// [SECTION] the manual capture

Status CaptureSessionOptions::validate() const {
  auto bad = [](const std::string& what) { return Error{"capture: " + what}; };
  if (directory.empty()) return bad("directory: give the folder to write");
  if (frames_per_pose < 1 || frames_per_pose > 30)
    return bad("frames_per_pose " + std::to_string(frames_per_pose) + " must be 1..30");
  if (!(settle_s >= 0.0 && settle_s <= 10.0))
    return bad("settle_s " + core::format_number(settle_s) + " must be 0..10 s");
  if (!(rest_tolerance_rad > 0.0)) return bad("the rest tolerance must be positive");
  if (!(rest_timeout_s > 0.0)) return bad("the rest timeout must be positive");
  if (Status s = hand_eye.validate(); !s) return bad(s.error().message);
  return {};
}

std::string CapturedPoseReport::summary() const {
  std::string seen;
  if (left_seen && right_seen) {
    seen = target + " seen left and right";
  } else if (left_seen || right_seen) {
    seen = target + " seen " + (left_seen ? "left only" : "right only");
  } else {
    seen = target + " not seen";
  }
  return "pose " + std::to_string(index) + ": " + std::to_string(frames) + " frame" +
         (frames == 1 ? "" : "s") + ", " + seen;
}

CaptureSession::CaptureSession(const core::RobotModel& model, net::RobotClient& robot,
                               net::VisionClient& vision, CaptureSessionOptions options)
    : model_(model), robot_(robot), vision_(vision), options_(std::move(options)) {}

Result<std::unique_ptr<CaptureSession>> CaptureSession::open(const core::RobotModel& model,
                                                             net::RobotClient& robot,
                                                             net::VisionClient& vision,
                                                             CaptureSessionOptions options) {
  if (Status s = options.validate(); !s) return s.error();
  if (!options.marker) {
    auto marker = core::marker_mount_for(model);
    if (!marker) return Error{"capture: marker: " + marker.error().message};
    options.marker = *marker;
  }
  auto info = open_capture_folder(vision, options.directory);
  if (!info) return info.error();
  std::unique_ptr<CaptureSession> session(
      new CaptureSession(model, robot, vision, std::move(options)));
  session->info_ = std::move(*info);
  CaptureSessionOptions& opened = session->options_;
  if (!opened.target) opened.target = vision::registration_target_from_mount(*opened.marker);
  vision::CaptureSet& capture = session->capture_;
  capture.robot = model.name();
  capture.target = opened.target->spec();
  if (Status s = write_capture_cameras(opened.directory, session->info_, capture); !s)
    return s.error();
  session->detected_.target = *opened.target;
  session->detected_.observations.target_points = opened.target->points();
  return session;
}

Result<net::RobotStateSample> CaptureSession::wait_for_rest() {
  auto state = robot_.wait_state(0, 5.0);
  if (!state) return Error{"no robot state from the robot server within 5 s"};
  const auto start = Clock::now();
  std::uint64_t sequence = state->sequence;
  while (core::seconds_since(start) < options_.rest_timeout_s) {
    if (cancel_) return Error{"cancelled: the capture was closed"};
    if (state->state.estop) return Error{"the robot is e-stopped: " + state->state.estop_reason};
    if (state->state.mode == core::RobotMode::kIdle && state->state.trajectory_id.empty()) {
      // Still there after settling: at rest, not between two jog steps.
      const Eigen::VectorXd q = state->state.q;
      std::this_thread::sleep_for(std::chrono::duration<double>(options_.settle_s));
      auto settled = robot_.wait_state(sequence, 1.0);
      if (!settled) return Error{"no robot state after settling"};
      if (settled->state.mode == core::RobotMode::kIdle &&
          (settled->state.q - q).cwiseAbs().maxCoeff() <= options_.rest_tolerance_rad) {
        return *settled;
      }
      state = settled;
      sequence = settled->sequence;
      continue;
    }
    auto next = robot_.wait_state(sequence, 1.0);
    if (!next) continue;
    state = next;
    sequence = next->sequence;
  }
  return Error{"the arm did not come to rest within " +
               core::format_fixed(options_.rest_timeout_s, 0) + " s (mode " +
               std::string(core::to_string(state->state.mode)) + ")"};
}

Result<CaptureSession::PoseCapture> CaptureSession::capture_pose(int index,
                                                                 std::uint64_t last_frame_id) {
  const std::string label = "pose " + std::to_string(index);
  auto rest = wait_for_rest();
  if (!rest) return Error{label + ": " + rest.error().message};
  PoseFramesOptions frames_options;
  frames_options.frames = options_.frames_per_pose;
  frames_options.max_sync_skew_ns = options_.max_sync_skew_ns;
  frames_options.timeout_s = options_.rest_timeout_s;
  PoseCapture out;
  out.index = index;
  out.last_frame_id = last_frame_id;
  auto frames = capture_pose_frames(vision_, options_.directory, index, *rest, frames_options,
                                    out.last_frame_id);
  if (!frames) return Error{label + ": " + frames.error().message};
  if (frames->empty()) {
    return Error{label + ": no synchronized stereo frame from the vision server within " +
                 core::format_fixed(options_.rest_timeout_s, 0) + " s after the arm settled"};
  }
  vision::CapturedPose& pose = out.pose;
  pose.q_commanded = rest->state.q_commanded.size() == rest->state.q.size()
                         ? rest->state.q_commanded
                         : rest->state.q;
  pose.q = rest->state.q;
  pose.joint_time_ns = rest->capture_ns;
  pose.frames = std::move(*frames);

  // The images must be the calibration's: a reduced or cropped stream would register nothing.
  vision::CaptureSet one;
  one.poses.push_back(pose);
  auto images = vision::read_captured_images(options_.directory, pose.frames.front());
  if (!images) return Error{label + ": " + images.error().message};
  const vision::CameraModel& left = info_.cameras.left;
  if (images->left.cols != left.width || images->left.rows != left.height) {
    return Error{label + ": the stream's images are " +
                 core::to_string(core::ImageSize{images->left.cols, images->left.rows}) +
                 ", the calibration's " +
                 core::to_string(core::ImageSize{left.width, left.height}) +
                 ": capture at the cameras' own size"};
  }
  auto detected = vision::detect_capture_targets(options_.directory, one, *options_.target);
  if (!detected) return Error{label + ": " + detected.error().message};
  out.detected = std::move(*detected);
  return out;
}

Result<CapturedPoseReport> CaptureSession::append_pose(PoseCapture captured) {
  const int index = captured.index;
  const std::string label = "pose " + std::to_string(index);
  capture_.poses.push_back(captured.pose);
  if (Status s = vision::write_capture_manifest(capture_, options_.directory); !s) {
    capture_.poses.pop_back();
    return Error{label + ": " + s.error().message};
  }
  last_frame_id_ = captured.last_frame_id;
  const vision::CaptureObservations& detected = captured.detected;
  CapturedPoseReport report;
  report.index = index;
  report.target = options_.target->is_board() ? "board" : "marker";
  report.frames = static_cast<int>(captured.pose.frames.size());
  report.q = captured.pose.q;
  vision::HandEyeView view = detected.observations.views.front();
  view.name = label;
  report.left_seen = !view.left.empty();
  report.right_seen = !view.right.empty();
  for (const std::string& note : detected.notes) {
    report.notes.push_back(renamed(note, index));
    detected_.notes.push_back(report.notes.back());
  }
  detected_.observations.views.push_back(std::move(view));
  detected_.left_found += detected.left_found;
  detected_.right_found += detected.right_found;
  reports_.push_back(report);
  ++revision_;
  return report;
}

Result<CapturedPoseReport> CaptureSession::add_current_pose() {
  if (adding()) return Error{"a pose is being added: wait for it"};
  auto captured = capture_pose(static_cast<int>(capture_.poses.size()), last_frame_id_);
  if (!captured) return captured.error();
  return append_pose(std::move(*captured));
}

Status CaptureSession::start_add_pose() {
  if (adding()) {
    return Error{"pose " + std::to_string(capture_.poses.size()) +
                 " is being added (waiting for the arm to come to rest): wait for it"};
  }
  const int index = static_cast<int>(capture_.poses.size());
  const std::uint64_t last_frame_id = last_frame_id_;
  cancel_ = false;
  pending_ = std::async(std::launch::async, [this, index, last_frame_id] {
    return capture_pose(index, last_frame_id);
  });
  ++revision_;
  return Status::Ok();
}

bool CaptureSession::adding() const {
  return pending_.valid();
}

std::optional<Result<CapturedPoseReport>> CaptureSession::poll_add() {
  if (!pending_.valid() ||
      pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    return std::nullopt;
  }
  auto captured = pending_.get();
  Result<CapturedPoseReport> added =
      captured ? append_pose(std::move(*captured)) : Result<CapturedPoseReport>(captured.error());
  last_add_error_ = added ? std::string() : added.error().message;
  ++adds_finished_;
  ++revision_;
  return added;
}

CaptureSession::~CaptureSession() {
  // The worker reads this session: stop its wait for rest and let it finish first.
  cancel_ = true;
  if (pending_.valid()) pending_.wait();
}

Result<vision::CaptureRegistration> CaptureSession::solve() {
  auto registration = vision::register_captures(model_, options_.directory, "", *options_.marker,
                                                options_.hand_eye, options_.target);
  ++revision_;
  if (!registration) {
    solve_error_ = registration.error().message;
    return registration.error();
  }
  solve_error_.clear();
  solution_ = *registration;
  return registration;
}

cv::Mat CaptureSession::coverage() const {
  return vision::coverage_image(detected_, info_.cameras.left.width, info_.cameras.left.height);
}

}  // namespace telear::session
