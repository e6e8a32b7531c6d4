#include "telear/view/ar_view_input.hpp"

namespace telear::view {

render::ArViewInput ar_view_input(const session::SessionView& view) {
  render::ArViewInput input;
  input.mode = view.display.mode == session::DisplayMode::kAR ? render::ViewMode::kAr
                                                              : render::ViewMode::kVr;
  input.stale = view.display.frame_stale;
  if (view.frame) {
    if (view.frame->left.empty() && !view.frame->left_planes.empty()) {
      input.left_planes = &view.frame->left_planes;  // decoded to planes: the GPU converts
      input.right_planes = &view.frame->right_planes;
    } else {
      input.left = &view.frame->left;
      input.right = &view.frame->right;
    }
  }
  input.ghost_q = view.ghost_q;
  input.ghost_gripper = view.ghost_gripper;
  input.ghost_highlight_frames = view.ghost_contact_frames;
  if (view.real) {
    input.reported_q = view.real->state.q;
    input.reported_gripper = view.real->state.gripper;
  }
  if (view.capture_arm) {
    input.capture_q = view.capture_arm->q;
    input.capture_gripper = view.capture_arm->gripper;
  }
  if (view.show_prediction) {
    input.predicted_q = view.prediction.q;
    input.predicted_gripper = view.prediction.gripper;
  }
  return input;
}

}  // namespace telear::view
