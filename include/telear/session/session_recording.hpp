#pragma once
// A session recorded to MCAP (telear console --record, telear demo --record): the one wiring of
// a Session's streams into a record::ServerRecorder, so that the console and the demo record
// the same things.
//
//   record_session_streams(options, recorder)   before Session::create: every frame the
//                                               session's vision client receives (its JPEGs
//                                               as received) and every session event -- with a
//                                               workflow step as a PlanEvent (and its Log),
//                                               the others as a Log -- and every robot state
//                                               its robot client receives
//   record_session_view(recorder, view, ...)    after each Session::update(): the ghost the
//                                               view draws, and the shown frame's latency
//
// The recorder must be started with recorder.ghost_from_state_stream = false (the ghost then
// comes from the view, once per displayed frame), stream_video = false and stream_state = false
// (the session's own streams feed it), and must outlive the session. Replay is exact when the
// view's time given to record_session_view is Session::state_taken_ns(): the states are
// logged at their receipt, and the view drew the newest received when its update took it.

#include <cstdint>
#include <optional>

#include "telear/record/server_recorder.hpp"
#include "telear/session/session.hpp"

namespace telear::session {

// The PlanEvent kind of a workflow step; nullopt for kNone.
std::optional<record::PlanEventKind> plan_event_kind(WorkflowStep step);

// Sets options.vision.on_received, options.robot.on_state and options.on_event (replacing
// what they held).
void record_session_streams(SessionOptions& options, record::ServerRecorder& recorder);

// `last_frame_id`: the caller's memory of the last frame whose latency was recorded (0 at the
// start). `monotonic_ns`: when the view is drawn.
void record_session_view(record::ServerRecorder& recorder, const SessionView& view,
                         std::uint64_t& last_frame_id, std::int64_t monotonic_ns);

}  // namespace telear::session
