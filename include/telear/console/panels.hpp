#pragma once
// The console's panels (Dear ImGui windows). Each draws the Session and the UiState and turns
// every button into a UiAction through PanelContext::act, the one code path shared with the
// keyboard, the input devices and scripts. Panels keep no state of their own.
//
//   connection_panel.cpp  addresses, token, connect / disconnect, lease, e-stop state, loss
//   view_panel.cpp        the stereo AR view and its graphics settings
//   real_robot_panel.cpp  joint read-outs with limit margins, initialize, direct jog
//   ghost_panel.cpp       joint sliders, +/- steps, Cartesian jog, gripper, named, ghost = real
//   plan_panel.cpp        waypoints, preview, validate, execute, cancel, progress, tracking
//   status_panel.cpp      fps, latency per stage, round trip, bandwidth, overlay error, events
//   registration_panel.cpp  the Session's registration capture: folder, add pose, per-eye
//                         detection, coverage, solve and its result (docs/console.md)
//   plots_panel.cpp       the session's live series: tracking error per joint, latency per
//                         stage, video fps and bandwidth, AR / VR, against time
//   estop_panel.cpp       the always-visible E-STOP button and the status bar

#include <functional>

#include "telear/console/ui_action.hpp"
#include "telear/console/ui_state.hpp"
#include "telear/session/session.hpp"

namespace telear::console {

struct PanelContext {
  session::Session& session;
  UiState& ui;
  std::function<void(const UiAction&)> act;  // apply_action plus the console's bookkeeping
};

// What the view panel shows: GL texture ids (bottom-up, as OffscreenTarget holds them) and
// their sizes.
struct ViewTextures {
  unsigned left = 0, right = 0, composed = 0;
  int eye_width = 0, eye_height = 0;
  int composed_width = 0, composed_height = 0;
};

// The registration capture's coverage image (both eyes side by side) as a GL texture, top row
// first; id 0: none yet.
struct CoverageTexture {
  unsigned id = 0;
  int width = 0, height = 0;
};

// Window placement for a display of width x height (first use; the operator may move them).
struct PanelLayout {
  float width = 1600, height = 1000;
  float view_w() const { return width * 0.69f; }
  float view_h() const { return height * 0.58f; }
  float bar_h() const { return 30.0f; }
};

void draw_connection_panel(PanelContext& ctx, const PanelLayout& layout);
// Returns whether the mouse is over the video image (for the mouse input device).
bool draw_view_panel(PanelContext& ctx, const PanelLayout& layout, const ViewTextures& textures);
void draw_real_robot_panel(PanelContext& ctx, const PanelLayout& layout);
void draw_ghost_panel(PanelContext& ctx, const PanelLayout& layout);
void draw_plan_panel(PanelContext& ctx, const PanelLayout& layout);
void draw_status_panel(PanelContext& ctx, const PanelLayout& layout);
// Drawn while ui.show_registration, over the plan and status panels.
void draw_registration_panel(PanelContext& ctx, const PanelLayout& layout,
                             const CoverageTexture& coverage);
// Drawn while ui.show_plots, over the plan and status panels.
void draw_plots_panel(PanelContext& ctx, const PanelLayout& layout);
void draw_estop_panel(PanelContext& ctx, const PanelLayout& layout);
void draw_status_bar(PanelContext& ctx, const PanelLayout& layout);

// Shared helpers (panel_widgets.cpp, ghost_panel.cpp).
void section(const char* title);  // a separator with a title
// BASE / WRIST / TOOL choice, step sizes and +/- buttons per axis, making `kind` actions
// (kGhostCartesian or kRealCartesian).
void draw_cartesian_jog(PanelContext& ctx, ActionKind kind);
// The margin to the nearer joint limit in the model's units; colour green / amber / red.
double limit_margin(const core::RobotModel& model, int joint, double q);
unsigned margin_colour(const core::RobotModel& model, int joint, double q);  // ImU32
bool is_prismatic(const core::RobotModel& model, int joint);
// Joint value for display: degrees, or millimetres for a prismatic joint.
double display_value(const core::RobotModel& model, int joint, double q);

}  // namespace telear::console
