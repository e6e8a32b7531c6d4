#pragma once
// The one code path of every operator action: buttons, keys, input devices and script lines
// all end here. apply_action() calls the Session (the state) or changes the UiState (how it
// is shown) and returns what happened; the message is also kept in ui.last_message for the
// status bar.

#include "telear/console/ui_action.hpp"
#include "telear/console/ui_state.hpp"
#include "telear/core/result.hpp"
#include "telear/session/session.hpp"
#include "telear/vision/hand_eye_registration.hpp"

namespace telear::console {

Status apply_action(session::Session& session, UiState& ui, const UiAction& action);

// Convenience builders used by panels and input devices.
UiAction ghost_joint(int joint, double delta);
UiAction ghost_cartesian(core::MotionFrame frame, const Eigen::Vector3d& dX,
                         const Eigen::Vector3d& dM);
UiAction simple(ActionKind kind);

// A solved registration in one line: the base's 1-sigma uncertainty (mm, deg), the poses used,
// the residuals per eye and the outliers dropped.
std::string registration_summary(const vision::HandEyeResult& result);

// The robot is idle: connected, state known, not executing, not moving (mode idle).
bool robot_idle(const session::Session& session);

}  // namespace telear::console
