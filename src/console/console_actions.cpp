#include "telear/console/console_actions.hpp"

#include <cmath>
#include <sstream>

#include "telear/core/angles.hpp"
#include "telear/session/capture_session.hpp"
#include "telear/session/plan_collision.hpp"

namespace telear::console {

namespace {

std::string fixed(double value, int decimals) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(decimals);
  out << value;
  return out.str();
}

Status from_outcome(const core::MotionOutcome& outcome) {
  if (!outcome.accepted) return Error{outcome.rejection.message};
  return Status::Ok();
}

Status dispatch(session::Session& s, UiState& ui, const UiAction& a) {
  switch (a.kind) {
    case ActionKind::kConnect:
      ui.reconnect_requested = true;  // the app rebuilds the session with ui's addresses
      return Status::Ok();
    case ActionKind::kDisconnect:
      s.disconnect();
      return Status::Ok();
    case ActionKind::kTakeControl:
      return s.take_control();
    case ActionKind::kReleaseControl:
      return s.release_control();
    case ActionKind::kEStop:
      return s.estop("e-stop from the console");
    case ActionKind::kResetEStop:
      return s.reset_estop();
    case ActionKind::kGhostJoint:
      return from_outcome(s.move_ghost(core::JointIncrement{a.index, a.value}));
    case ActionKind::kGhostCartesian:
      return from_outcome(s.move_ghost(core::CartesianIncrement{a.frame, a.dX, a.dM}));
    case ActionKind::kGhostGripper:
      return s.ghost().set_gripper(a.value);
    case ActionKind::kGhostNamed:
      return from_outcome(s.ghost().go_to(a.text));
    case ActionKind::kGhostToReal:
      return s.ghost_to_real();
    case ActionKind::kRealJoint: {
      auto ack = s.jog_real(core::JointIncrement{a.index, a.value});
      return ack ? Status::Ok() : Status(ack.error());
    }
    case ActionKind::kRealCartesian: {
      auto ack = s.jog_real(core::CartesianIncrement{a.frame, a.dX, a.dM});
      return ack ? Status::Ok() : Status(ack.error());
    }
    case ActionKind::kRealGripper:
      return s.set_real_gripper(a.value);
    case ActionKind::kRealInitialize: {
      Eigen::VectorXd q = a.q;
      if (!a.text.empty()) {
        auto named = s.model().named_configuration(a.text);
        if (!named) {
          return Error{"unknown configuration '" + a.text +
                       "' (known: " + session::named_configuration_list(s.model()) + ")"};
        }
        q = *named;
      }
      if (q.size() != s.model().dof()) {
        return Error{"initialize: " + std::to_string(s.model().dof()) +
                     " joint values needed, got " + std::to_string(q.size())};
      }
      auto ack = s.initialize_real(q);
      return ack ? Status::Ok() : Status(ack.error());
    }
    case ActionKind::kPlanAdd:
      return s.add_ghost_waypoint(a.value, a.text);
    case ActionKind::kPlanDelete:
      return s.plan().remove(static_cast<std::size_t>(a.index));
    case ActionKind::kPlanMove:
      return s.plan().move(static_cast<std::size_t>(a.index), static_cast<std::size_t>(a.index2));
    case ActionKind::kPlanDuration:
      return s.plan().set_min_duration(static_cast<std::size_t>(a.index), a.value);
    case ActionKind::kPlanClear:
      s.stop_preview();
      s.plan().clear();
      return Status::Ok();
    case ActionKind::kPlanSave:
      return s.plan().save(a.text);
    case ActionKind::kPlanLoad: {
      auto plan = session::Plan::load(s.plan().model_ptr(), a.text);
      if (!plan) return plan.error();
      s.stop_preview();
      s.plan() = std::move(*plan);
      return Status::Ok();
    }
    case ActionKind::kPreviewPlay:
      if (!s.preview()) return s.start_preview();
      s.preview()->play();
      return Status::Ok();
    case ActionKind::kPreviewPause:
      if (s.preview()) s.preview()->pause();
      return Status::Ok();
    case ActionKind::kPreviewStop:
      s.stop_preview();
      return Status::Ok();
    case ActionKind::kPreviewSeek:
      if (!s.preview()) {
        if (Status st = s.start_preview(); !st.ok()) return st;
      }
      s.preview()->seek(a.value);
      return Status::Ok();
    case ActionKind::kPreviewSpeed:
      if (!s.preview()) return Error{"no preview running"};
      return s.preview()->set_speed(a.value);
    case ActionKind::kValidate: {
      const session::ValidationReport report = s.validate_plan();
      ui.validation_text = report.summary();
      ui.validation_collision =
          report.collision ? session::collision_summary(*report.collision) : std::string();
      ui.validation_collision_free = !report.collision || report.collision->collision_free();
      if (!report.ok()) return Error{report.summary()};
      ui.last_message = "validation: " + report.summary();
      return Status::Ok();
    }
    case ActionKind::kExecute: {
      s.stop_preview();
      auto ack = s.execute_plan();
      return ack ? Status::Ok() : Status(ack.error());
    }
    case ActionKind::kCancel:
      return s.cancel_execution();
    case ActionKind::kViewLayout: {
      auto layout = parse_layout(a.text);
      if (!layout) {
        return Error{"unknown layout '" + a.text +
                     "' (known: sbs, tb, anaglyph, left, right, separate, page-flip)"};
      }
      ui.layout = *layout;
      return Status::Ok();
    }
    case ActionKind::kViewStyle:
      if (a.text != "solid" && a.text != "wire") {
        return Error{"style '" + a.text + "': solid or wire"};
      }
      ui.wireframe = a.text == "wire";
      return Status::Ok();
    case ActionKind::kViewSegments:
      if (a.index != 0 && (a.index < 3 || a.index > 512)) {
        return Error{"segments " + std::to_string(a.index) + ": 0 (the body's own) or 3..512"};
      }
      if (ui.segments != a.index) ui.body_dirty = true;
      ui.segments = a.index;
      return Status::Ok();
    case ActionKind::kViewOpacity:
      if (!(a.value > 0.0 && a.value <= 1.0)) return Error{"opacity must be in (0, 1]"};
      ui.ghost_opacity = static_cast<float>(a.value);
      return Status::Ok();
    case ActionKind::kViewVideo:
      if (a.text != "raw" && a.text != "undistorted") {
        return Error{"video '" + a.text + "': raw or undistorted"};
      }
      ui.undistorted = a.text == "undistorted";
      return Status::Ok();
    case ActionKind::kViewMode:
      if (a.text == "auto") {
        s.display().set_preference(session::DisplayPreference::kAutomatic);
      } else if (a.text == "ar") {
        s.display().set_preference(session::DisplayPreference::kAR);
      } else if (a.text == "vr") {
        s.display().set_preference(session::DisplayPreference::kVR);
      } else {
        return Error{"mode '" + a.text + "': auto, ar or vr"};
      }
      return Status::Ok();
    case ActionKind::kViewReported:
      ui.show_reported = a.value != 0.0;
      return Status::Ok();
    case ActionKind::kViewPredicted:
      ui.show_predicted = a.value != 0.0;
      break;
    case ActionKind::kViewCapture:
      ui.show_capture_arm = a.value != 0.0;
      return Status::Ok();
    case ActionKind::kViewPlots:
      ui.show_plots = a.value != 0.0;
      return Status::Ok();
    case ActionKind::kCaptureOpen: {
      if (a.text.empty()) return Error{"give the folder to write the capture into"};
      session::CaptureSessionOptions options;
      options.directory = a.text;
      if (!a.spec.empty()) {
        auto target = vision::parse_registration_target(a.spec);
        if (!target) return Error{"registration: " + target.error().message};
        options.target = *target;
      }
      if (Status st = s.open_capture(std::move(options)); !st.ok()) return st;
      ui.show_registration = true;
      ui.last_message = "registration: capturing into " + a.text +
                        "; jog the real arm until both cameras see the " +
                        s.capture()->target().description() + ", then add the pose";
      return Status::Ok();
    }
    case ActionKind::kCaptureAdd: {
      if (!s.capture()) return Error{"no capture open: open one on a folder first"};
      // On the capture's worker: the console stays live while the arm comes to rest; the
      // session appends the pose when it is done (and logs it).
      if (Status st = s.capture()->start_add_pose(); !st.ok()) return st;
      ui.last_message = "registration: adding pose " + std::to_string(s.capture()->poses().size()) +
                        " (when the arm is at rest)";
      return Status::Ok();
    }
    case ActionKind::kCaptureSolve: {
      if (!s.capture()) return Error{"no capture open: open one on a folder first"};
      auto solved = s.capture()->solve();
      if (!solved) return solved.error();
      ui.last_message = "registration: " + registration_summary(solved->result);
      return Status::Ok();
    }
    case ActionKind::kCaptureClose:
      s.close_capture();
      return Status::Ok();
    case ActionKind::kScreenshot:
      ui.screenshot_request = a.text;
      return Status::Ok();
    case ActionKind::kQuit:
      ui.quit = true;
      return Status::Ok();
  }
  return Error{"unknown action"};
}

}  // namespace

std::string registration_summary(const vision::HandEyeResult& result) {
  int dropped = 0;
  for (const vision::ViewFit& view : result.views) dropped += view.dropped;
  return "base +-" + fixed(result.base_sigma.position_mm, 2) + " mm +-" +
         fixed(result.base_sigma.rotation_deg, 3) + " deg (1 sigma) from " +
         std::to_string(result.views_used) + " poses, rms " + fixed(result.left.rms_px, 2) + " / " +
         fixed(result.right.rms_px, 2) + " px" +
         (dropped > 0 ? ", " + std::to_string(dropped) + " dropped as outliers" : "");
}

const char* to_string(ActionKind kind) {
  switch (kind) {
    case ActionKind::kConnect:
      return "connect";
    case ActionKind::kDisconnect:
      return "disconnect";
    case ActionKind::kTakeControl:
      return "take control";
    case ActionKind::kReleaseControl:
      return "release control";
    case ActionKind::kEStop:
      return "e-stop";
    case ActionKind::kResetEStop:
      return "reset e-stop";
    case ActionKind::kGhostJoint:
      return "ghost joint";
    case ActionKind::kGhostCartesian:
      return "ghost cartesian";
    case ActionKind::kGhostGripper:
      return "ghost gripper";
    case ActionKind::kGhostNamed:
      return "ghost named";
    case ActionKind::kGhostToReal:
      return "ghost = real";
    case ActionKind::kRealJoint:
      return "real jog joint";
    case ActionKind::kRealCartesian:
      return "real jog cartesian";
    case ActionKind::kRealGripper:
      return "real gripper";
    case ActionKind::kRealInitialize:
      return "real initialize";
    case ActionKind::kPlanAdd:
      return "plan add";
    case ActionKind::kPlanDelete:
      return "plan delete";
    case ActionKind::kPlanMove:
      return "plan move";
    case ActionKind::kPlanDuration:
      return "plan duration";
    case ActionKind::kPlanClear:
      return "plan clear";
    case ActionKind::kPlanSave:
      return "plan save";
    case ActionKind::kPlanLoad:
      return "plan load";
    case ActionKind::kPreviewPlay:
      return "preview play";
    case ActionKind::kPreviewPause:
      return "preview pause";
    case ActionKind::kPreviewStop:
      return "preview stop";
    case ActionKind::kPreviewSeek:
      return "preview seek";
    case ActionKind::kPreviewSpeed:
      return "preview speed";
    case ActionKind::kValidate:
      return "validate";
    case ActionKind::kExecute:
      return "execute";
    case ActionKind::kCancel:
      return "cancel";
    case ActionKind::kViewLayout:
      return "view layout";
    case ActionKind::kViewStyle:
      return "view style";
    case ActionKind::kViewSegments:
      return "view segments";
    case ActionKind::kViewOpacity:
      return "view opacity";
    case ActionKind::kViewVideo:
      return "view video";
    case ActionKind::kViewMode:
      return "view mode";
    case ActionKind::kViewReported:
      return "view reported";
    case ActionKind::kViewPredicted:
      return "view predicted";
    case ActionKind::kViewCapture:
      return "view capture";
    case ActionKind::kViewPlots:
      return "view plots";
    case ActionKind::kCaptureOpen:
      return "registration open";
    case ActionKind::kCaptureAdd:
      return "registration add";
    case ActionKind::kCaptureSolve:
      return "registration solve";
    case ActionKind::kCaptureClose:
      return "registration close";
    case ActionKind::kScreenshot:
      return "screenshot";
    case ActionKind::kQuit:
      return "quit";
  }
  return "?";
}

Status apply_action(session::Session& session, UiState& ui, const UiAction& action) {
  ui.last_message.clear();
  Status status = dispatch(session, ui, action);
  if (!status.ok()) {
    ui.last_message = std::string(to_string(action.kind)) + ": " + status.error().message;
    ui.last_failed = true;
  } else {
    if (ui.last_message.empty()) ui.last_message = std::string(to_string(action.kind)) + ": ok";
    ui.last_failed = false;
  }
  return status;
}

UiAction ghost_joint(int joint, double delta) {
  UiAction a;
  a.kind = ActionKind::kGhostJoint;
  a.index = joint;
  a.value = delta;
  return a;
}

UiAction ghost_cartesian(core::MotionFrame frame, const Eigen::Vector3d& dX,
                         const Eigen::Vector3d& dM) {
  UiAction a;
  a.kind = ActionKind::kGhostCartesian;
  a.frame = frame;
  a.dX = dX;
  a.dM = dM;
  return a;
}

UiAction simple(ActionKind kind) {
  UiAction a;
  a.kind = kind;
  return a;
}

bool robot_idle(const session::Session& session) {
  const auto& real = session.view().real;
  return session.robot_connected() && real && !session.executing() &&
         real->state.mode == core::RobotMode::kIdle;
}

}  // namespace telear::console
