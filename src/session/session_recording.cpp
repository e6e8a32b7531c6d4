#include "telear/session/session_recording.hpp"

namespace telear::session {

std::optional<record::PlanEventKind> plan_event_kind(WorkflowStep step) {
  using K = record::PlanEventKind;
  switch (step) {
    case WorkflowStep::kNone:
      return std::nullopt;
    case WorkflowStep::kLeaseAcquired:
      return K::kLeaseAcquired;
    case WorkflowStep::kLeaseReleased:
      return K::kLeaseReleased;
    case WorkflowStep::kPreview:
      return K::kPreview;
    case WorkflowStep::kValidate:
      return K::kValidate;
    case WorkflowStep::kExecute:
      return K::kExecute;
    case WorkflowStep::kCollision:
      return K::kCollision;
    case WorkflowStep::kDisplayMode:
      return K::kDisplayMode;
    case WorkflowStep::kEStop:
      return K::kEStop;
    case WorkflowStep::kEStopReset:
      return K::kEStopReset;
    case WorkflowStep::kFault:
      return K::kFault;
  }
  return std::nullopt;
}

void record_session_streams(SessionOptions& options, record::ServerRecorder& recorder) {
  options.vision.on_received = [raw = &recorder](const net::ReceivedStereoFrame& frame) {
    raw->add_frame(frame);
  };
  // Every state the session's client receives, logged at its receipt: the view drew the newest
  // one received before its update took it (Session::state_taken_ns, the view's time).
  options.robot.on_state = [raw = &recorder](const net::RobotStateSample& sample) {
    raw->add_state(sample);
  };
  options.on_event = [raw = &recorder](const SessionEvent& e, std::int64_t monotonic_ns) {
    if (const auto kind = plan_event_kind(e.step)) {
      raw->add_plan_event(*kind, e.message, e.plan_id, e.plan_hash, monotonic_ns);
      return;
    }
    raw->add_log(e.kind == SessionEvent::Kind::kError     ? record::LogLevel::kError
                 : e.kind == SessionEvent::Kind::kWarning ? record::LogLevel::kWarning
                                                          : record::LogLevel::kInfo,
                 e.message, monotonic_ns);
  };
}

void record_session_view(record::ServerRecorder& recorder, const SessionView& view,
                         std::uint64_t& last_frame_id, std::int64_t monotonic_ns) {
  if (view.ghost_q.size() > 0) recorder.add_ghost(view.ghost_q, view.ghost_gripper, monotonic_ns);
  if (view.frame && view.frame->frame_id != last_frame_id) {
    last_frame_id = view.frame->frame_id;
    // Logged at the view's time, not the decode's: a frame decoded while this update ran is
    // not the one the view drew, and replay at this time must not show it.
    recorder.add_latency(*view.frame, monotonic_ns);
  }
}

}  // namespace telear::session
