#include <imgui.h>

#include <cmath>

#include "telear/console/console_actions.hpp"
#include "telear/console/panels.hpp"
#include "telear/core/angles.hpp"

namespace telear::console {

namespace {

// Six +/- buttons for the Cartesian axes; `kind` is the ghost's or the real robot's action.
void cartesian_buttons(PanelContext& ctx, ActionKind kind) {
  const UiState& ui = ctx.ui;
  const double step_m = ui.cartesian_step_mm / 1000.0;
  const double step_rad = core::radians_from_degrees(ui.rotation_step_deg);
  static const char* axes[] = {"x", "y", "z", "rx", "ry", "rz"};
  for (int k = 0; k < 6; ++k) {
    for (int sign : {-1, +1}) {
      ImGui::PushID(k * 2 + (sign > 0));
      char label[16];
      std::snprintf(label, sizeof label, "%s%s", axes[k], sign > 0 ? "+" : "-");
      if (ImGui::Button(label, ImVec2(38, 0))) {
        UiAction a{.kind = kind, .frame = ui.frame};
        if (k < 3) {
          a.dX[k] = sign * step_m;
        } else {
          a.dM[k - 3] = sign * step_rad;
        }
        ctx.act(a);
      }
      ImGui::PopID();
      ImGui::SameLine();
    }
    if (k == 2) ImGui::NewLine();
  }
  ImGui::NewLine();
}

}  // namespace

void draw_cartesian_jog(PanelContext& ctx, ActionKind kind) {
  UiState& ui = ctx.ui;
  int frame = static_cast<int>(ui.frame);
  ImGui::RadioButton("BASE", &frame, 0);
  ImGui::SameLine();
  ImGui::RadioButton("WRIST", &frame, 1);
  ImGui::SameLine();
  ImGui::RadioButton("TOOL", &frame, 2);
  ui.frame = static_cast<core::MotionFrame>(frame);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputFloat("mm", &ui.cartesian_step_mm, 0, 0, "%.1f");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(60);
  ImGui::InputFloat("deg##rot", &ui.rotation_step_deg, 0, 0, "%.1f");
  ui.cartesian_step_mm = std::clamp(ui.cartesian_step_mm, 0.1f, 200.0f);
  ui.rotation_step_deg = std::clamp(ui.rotation_step_deg, 0.1f, 90.0f);
  cartesian_buttons(ctx, kind);
}

void draw_ghost_panel(PanelContext& ctx, const PanelLayout& layout) {
  session::Session& s = ctx.session;
  UiState& ui = ctx.ui;
  const core::RobotModel& model = s.model();
  ImGui::SetNextWindowPos(ImVec2(layout.view_w(), 270), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(layout.width - layout.view_w(), 370), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Ghost")) {
    ImGui::End();
    return;
  }
  ImGui::SetNextItemWidth(80);
  ImGui::InputFloat("joint step (deg / mm)", &ui.joint_step_deg, 0, 0, "%.2f");
  ui.joint_step_deg = std::clamp(ui.joint_step_deg, 0.01f, 45.0f);
  const Eigen::VectorXd& q = s.ghost().q();
  const bool busy = s.view().previewing || s.view().executing;
  for (int j = 0; j < model.dof(); ++j) {
    ImGui::PushID(j);
    const bool prismatic = is_prismatic(model, j);
    const double unit =
        prismatic ? 1e-3 : core::radians_from_degrees(1.0);  // UI unit in model units
    const double step = ui.joint_step_deg * unit;
    if (ImGui::Button("-")) ctx.act(ghost_joint(j, -step));
    ImGui::SameLine();
    const core::JointLimits& l = model.joint(j).limits;
    float value = static_cast<float>(display_value(model, j, q[j]));
    ImGui::PushStyleColor(ImGuiCol_SliderGrab, margin_colour(model, j, q[j]));
    ImGui::SetNextItemWidth(200);
    char label[64];
    std::snprintf(label, sizeof label, "%s", model.joint(j).name.c_str());
    if (ImGui::SliderFloat(label, &value, static_cast<float>(display_value(model, j, l.lower)),
                           static_cast<float>(display_value(model, j, l.upper)),
                           prismatic ? "%.1f mm" : "%.1f deg")) {
      ctx.act(ghost_joint(j, value * unit - q[j]));
    }
    ImGui::PopStyleColor();
    ImGui::SameLine();
    if (ImGui::Button("+")) ctx.act(ghost_joint(j, step));
    ImGui::SameLine();
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(margin_colour(model, j, q[j])), "%5.1f",
                       display_value(model, j, limit_margin(model, j, q[j])));
    ImGui::PopID();
  }
  if (busy)
    ImGui::TextDisabled("(the ghost follows the %s)", s.view().executing ? "execution" : "preview");
  section("Cartesian");
  draw_cartesian_jog(ctx, ActionKind::kGhostCartesian);
  const Eigen::Vector3d p = s.ghost().T_base_tool().translation();
  ImGui::Text("tool at (%.3f, %.3f, %.3f) m", p.x(), p.y(), p.z());
  if (s.checks_collisions()) {
    // The ghost's clearance where it is drawn: red on contact, amber under the safety margin.
    using Level = session::ClearanceState::Level;
    const session::ClearanceState& c = s.ghost_clearance();
    const ImVec4 colour = c.level == Level::kContact        ? ImVec4(1.0f, 0.3f, 0.3f, 1)
                          : c.level == Level::kWithinMargin ? ImVec4(1.0f, 0.7f, 0.1f, 1)
                                                            : ImVec4(0.6f, 0.9f, 0.6f, 1);
    ImGui::TextColored(colour, "%s", c.summary().c_str());
  }
  section("Gripper and configurations");
  if (ImGui::Button("Open")) ctx.act({.kind = ActionKind::kGhostGripper, .value = 1.0});
  ImGui::SameLine();
  if (ImGui::Button("Close")) ctx.act({.kind = ActionKind::kGhostGripper, .value = 0.0});
  ImGui::SameLine();
  ImGui::Text("gripper %.2f", s.ghost().gripper());
  const auto& named = model.named_configurations();
  for (std::size_t i = 0; i < named.size(); ++i) {
    if (i) ImGui::SameLine();
    if (ImGui::Button(named[i].name.c_str())) {
      ctx.act({.kind = ActionKind::kGhostNamed, .text = named[i].name});
    }
  }
  if (!named.empty()) ImGui::SameLine();
  if (ImGui::Button("Ghost = real")) ctx.act(simple(ActionKind::kGhostToReal));
  ImGui::End();
}

}  // namespace telear::console
