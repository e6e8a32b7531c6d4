#include <imgui.h>

#include <algorithm>
#include <cstdint>

#include "telear/console/console_actions.hpp"
#include "telear/console/panels.hpp"

#include "imgui_texture.hpp"

namespace telear::console {

namespace {

// Draws a bottom-up GL texture of w x h fitted into `avail` (aspect kept); returns hovered.
bool fitted_image(unsigned id, int w, int h, ImVec2 avail) {
  if (id == 0 || w <= 0 || h <= 0 || avail.x < 8 || avail.y < 8) return false;
  const float scale = std::min(avail.x / static_cast<float>(w), avail.y / static_cast<float>(h));
  ImGui::Image(texture(id), ImVec2(w * scale, h * scale), ImVec2(0, 1), ImVec2(1, 0));
  return ImGui::IsItemHovered();
}

}  // namespace

bool draw_view_panel(PanelContext& ctx, const PanelLayout& layout, const ViewTextures& t) {
  session::Session& s = ctx.session;
  UiState& ui = ctx.ui;
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(layout.view_w(), layout.view_h()), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Stereo AR view")) {
    ImGui::End();
    return false;
  }
  // [SECTION] settings row
  static const char* layouts[] = {
      "side by side",           "top-bottom", "anaglyph", "left eye", "right eye", "both eyes",
      "page flip (quad buffer)"};
  int layout_index = static_cast<int>(ui.layout);
  ImGui::SetNextItemWidth(150);
  if (ImGui::Combo("##layout", &layout_index, layouts, IM_ARRAYSIZE(layouts))) {
    ctx.act({.kind = ActionKind::kViewLayout,
             .text = layout_name(static_cast<ViewLayout>(layout_index))});
  }
  ImGui::SameLine();
  int style = ui.wireframe ? 1 : 0;
  if (ImGui::RadioButton("solid", &style, 0))
    ctx.act({.kind = ActionKind::kViewStyle, .text = "solid"});
  ImGui::SameLine();
  if (ImGui::RadioButton("wire", &style, 1))
    ctx.act({.kind = ActionKind::kViewStyle, .text = "wire"});
  ImGui::SameLine();
  int segments = ui.segments;
  ImGui::SetNextItemWidth(90);
  if (ImGui::SliderInt("segments", &segments, 0, 64, segments == 0 ? "body" : "%d")) {
    ctx.act(
        {.kind = ActionKind::kViewSegments, .index = segments < 3 && segments > 0 ? 3 : segments});
  }
  ImGui::SameLine();
  float opacity = ui.ghost_opacity;
  ImGui::SetNextItemWidth(90);
  if (ImGui::SliderFloat("ghost", &opacity, 0.05f, 1.0f, "%.2f")) {
    ctx.act({.kind = ActionKind::kViewOpacity, .value = opacity});
  }
  ImGui::SameLine();
  bool reported = ui.show_reported;
  if (ImGui::Checkbox("reported", &reported)) {
    ctx.act({.kind = ActionKind::kViewReported, .value = reported ? 1.0 : 0.0});
  }
  ImGui::SameLine();
  bool predicted = ui.show_predicted;
  if (ImGui::Checkbox("predicted", &predicted)) {
    ctx.act({.kind = ActionKind::kViewPredicted, .value = predicted ? 1.0 : 0.0});
  }
  ImGui::SameLine();
  bool at_capture = ui.show_capture_arm;
  if (ImGui::Checkbox("at capture", &at_capture)) {
    ctx.act({.kind = ActionKind::kViewCapture, .value = at_capture ? 1.0 : 0.0});
  }
  ImGui::SameLine();
  bool undistorted = ui.undistorted;
  if (ImGui::Checkbox("undistort", &undistorted)) {
    ctx.act({.kind = ActionKind::kViewVideo, .text = undistorted ? "undistorted" : "raw"});
  }
  ImGui::SameLine();
  static const char* modes[] = {"auto", "ar", "vr"};
  int mode = static_cast<int>(s.display().preference());
  ImGui::SetNextItemWidth(70);
  if (ImGui::Combo("mode", &mode, modes, 3))
    ctx.act({.kind = ActionKind::kViewMode, .text = modes[mode]});

  // [SECTION] what the operator is looking at
  const session::SessionView& v = s.view();
  const bool ar = v.display.mode == session::DisplayMode::kAR;
  ImGui::TextColored(ar ? ImVec4(0.35f, 0.85f, 0.35f, 1) : ImVec4(1, 0.7f, 0.2f, 1), "%s",
                     ar ? "AR (live video)" : "VR (virtual scene)");
  ImGui::SameLine();
  if (v.display.frame_age) {
    ImGui::Text("frame age %.0f ms", *v.display.frame_age * 1e3);
  } else {
    ImGui::TextDisabled("no video yet");
  }
  if (v.display.frame_stale) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1, 0.25f, 0.2f, 1), "STALE%s",
                       v.display.stream_stopped ? " (stopped)" : "");
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%s", v.display.reason.c_str());
  // Which arm is which (render::ArViewOptions' colours), and what the predictor says.
  ImGui::TextColored(ImVec4(0.2f, 0.75f, 1, 1), "ghost: plan");
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(1, 0.85f, 0.2f, 1), "yellow: reported (as late as the state)");
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(0.95f, 0.2f, 0.9f, 1), "magenta wire: predicted now");
  ImGui::SameLine();
  if (ui.show_capture_arm) {
    ImGui::TextColored(ImVec4(0.95f, 0.95f, 0.95f, 1), "white wire: at the frame's capture");
    ImGui::SameLine();
  }
  if (v.show_prediction && ui.show_predicted) {
    ImGui::Text("%s", v.prediction.summary().c_str());
  } else {
    ImGui::TextDisabled("%s", v.prediction.available ? "prediction not drawn: the state is fresh"
                                                     : v.prediction.summary().c_str());
  }
  if (ui.layout == ViewLayout::kPageFlip && !ui.page_flip_granted) {
    ImGui::TextColored(ImVec4(1, 0.7f, 0.2f, 1), "%s", ui.page_flip_message.c_str());
  }

  // [SECTION] the image(s)
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  bool hovered = false;
  switch (ui.layout) {
    case ViewLayout::kLeftEye:
      hovered = fitted_image(t.left, t.eye_width, t.eye_height, avail);
      break;
    case ViewLayout::kRightEye:
      hovered = fitted_image(t.right, t.eye_width, t.eye_height, avail);
      break;
    case ViewLayout::kSeparate: {
      const ImVec2 half(avail.x / 2 - 4, avail.y);
      hovered = fitted_image(t.left, t.eye_width, t.eye_height, half);
      ImGui::SameLine();
      hovered = fitted_image(t.right, t.eye_width, t.eye_height, half) || hovered;
      break;
    }
    case ViewLayout::kPageFlip:
      if (ui.page_flip_granted) {  // the right buffer's pass swaps in the right eye's texture
        hovered = fitted_image(t.left, t.eye_width, t.eye_height, avail);
        break;
      }
      [[fallthrough]];
    default:
      hovered = fitted_image(t.composed, t.composed_width, t.composed_height, avail);
  }
  ImGui::End();
  return hovered;
}

}  // namespace telear::console
