#include <imgui.h>

#include "telear/console/panels.hpp"

namespace telear::console {

namespace {
void led(bool on, const char* label) {
  ImGui::TextColored(on ? ImVec4(0.35f, 0.85f, 0.35f, 1) : ImVec4(0.95f, 0.3f, 0.25f, 1), "%s %s",
                     on ? "[on ]" : "[off]", label);
}
}  // namespace

void draw_connection_panel(PanelContext& ctx, const PanelLayout& layout) {
  session::Session& s = ctx.session;
  UiState& ui = ctx.ui;
  ImGui::SetNextWindowPos(ImVec2(layout.view_w(), 70), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(layout.width - layout.view_w(), 200), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Connection")) {
    ImGui::End();
    return;
  }
  ImGui::PushItemWidth(220);
  ImGui::InputText("robot server", ui.robot_address, sizeof ui.robot_address);
  ImGui::InputText("vision server", ui.vision_address, sizeof ui.vision_address);
  ImGui::InputText("token", ui.token, sizeof ui.token, ImGuiInputTextFlags_Password);
  ImGui::PopItemWidth();
  if (ui.embedded) {
    ImGui::SameLine();
    ImGui::TextDisabled("(embedded sim)");
  }
  if (ImGui::Button("Connect")) ctx.act({.kind = ActionKind::kConnect});
  ImGui::SameLine();
  if (ImGui::Button("Disconnect")) ctx.act({.kind = ActionKind::kDisconnect});
  ImGui::SameLine();
  if (s.in_control()) {
    if (ImGui::Button("Release control")) ctx.act({.kind = ActionKind::kReleaseControl});
  } else if (ImGui::Button("Take control")) {
    ctx.act({.kind = ActionKind::kTakeControl});
  }
  ImGui::SameLine();
  ImGui::Checkbox("Registration", &ui.show_registration);  // the panel (registration_panel.cpp)
  ImGui::SameLine();
  if (bool plots = ui.show_plots; ImGui::Checkbox("Plots", &plots)) {  // plots_panel.cpp
    ctx.act({.kind = ActionKind::kViewPlots, .value = plots ? 1.0 : 0.0});
  }

  const bool robot = s.robot_connected(), vision = s.vision_connected();
  led(robot, "robot");
  ImGui::SameLine();
  led(vision, "video");
  ImGui::SameLine();
  led(s.in_control(), "lease held");
  if (s.connected() && (!robot || !vision)) {
    ImGui::TextColored(ImVec4(1, 0.3f, 0.25f, 1), "CONNECTION LOST: %s%s%s - reconnecting",
                       robot ? "" : "robot", !robot && !vision ? ", " : "", vision ? "" : "video");
  } else if (!s.connected()) {
    ImGui::TextColored(ImVec4(0.9f, 0.7f, 0.2f, 1), "disconnected");
  }
  const std::string lease_error = s.robot().lease_error();
  if (!lease_error.empty()) ImGui::TextWrapped("lease: %s", lease_error.c_str());
  const auto& real = s.view().real;
  if (real && real->state.estop) {
    ImGui::TextColored(ImVec4(1, 0.25f, 0.2f, 1), "E-STOP ENGAGED: %s",
                       real->state.estop_reason.c_str());
    ImGui::SameLine();
    if (ImGui::Button("Reset e-stop")) ctx.act({.kind = ActionKind::kResetEStop});
  } else if (real) {
    ImGui::Text("robot: %s, lease holder '%s'", to_string(real->state.mode),
                real->lease_holder.c_str());
  }
  ImGui::End();
}

}  // namespace telear::console
