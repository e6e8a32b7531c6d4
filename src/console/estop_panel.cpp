#include <imgui.h>

#include "telear/console/console_actions.hpp"
#include "telear/console/panels.hpp"

namespace telear::console {

void draw_estop_panel(PanelContext& ctx, const PanelLayout& layout) {
  ImGui::SetNextWindowPos(ImVec2(layout.view_w(), 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(layout.width - layout.view_w(), 70), ImGuiCond_Always);
  ImGui::Begin("##estop", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
  ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.8f, 0.08f, 0.05f, 1));
  ImGui::PushStyleColor(ImGuiCol_ButtonHovered, ImVec4(0.95f, 0.15f, 0.1f, 1));
  ImGui::PushStyleColor(ImGuiCol_ButtonActive, ImVec4(1, 0.3f, 0.2f, 1));
  if (ImGui::Button("E-STOP  (Space / Esc)", ImVec2(230, 52))) ctx.act(simple(ActionKind::kEStop));
  ImGui::PopStyleColor(3);
  ImGui::SameLine();
  const auto& real = ctx.session.view().real;
  ImGui::BeginGroup();
  if (real && real->state.estop) {
    ImGui::TextColored(ImVec4(1, 0.25f, 0.2f, 1), "E-STOP ENGAGED");
    if (ImGui::Button("Reset e-stop")) ctx.act(simple(ActionKind::kResetEStop));
  } else {
    ImGui::Text("robot: %s", real ? to_string(real->state.mode) : "no state");
    ImGui::Text("%s",
                ctx.session.in_control() ? "in control (lease held)" : "observing (no lease)");
  }
  ImGui::EndGroup();
  ImGui::End();
}

void draw_status_bar(PanelContext& ctx, const PanelLayout& layout) {
  ImGui::SetNextWindowPos(ImVec2(0, layout.height - layout.bar_h()), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(layout.width, layout.bar_h()), ImGuiCond_Always);
  ImGui::Begin(
      "##statusbar", nullptr,
      ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);
  const UiState& ui = ctx.ui;
  ImGui::TextColored(ui.last_failed ? ImVec4(1, 0.4f, 0.35f, 1) : ImVec4(0.75f, 0.9f, 0.75f, 1),
                     "%s", ui.last_message.empty() ? "ready" : ui.last_message.c_str());
  if (!ui.calibration_note.empty()) {
    ImGui::SameLine(layout.width * 0.55f);
    ImGui::TextDisabled("%s", ui.calibration_note.c_str());
  }
  ImGui::End();
}

}  // namespace telear::console
