#include <imgui.h>

#include <cmath>

#include "telear/console/console_actions.hpp"
#include "telear/console/panels.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/number_list.hpp"

namespace telear::console {

void draw_real_robot_panel(PanelContext& ctx, const PanelLayout& layout) {
  session::Session& s = ctx.session;
  UiState& ui = ctx.ui;
  const core::RobotModel& model = s.model();
  const float y = 640;
  ImGui::SetNextWindowPos(ImVec2(layout.view_w(), y), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(
      ImVec2(layout.width - layout.view_w(), layout.height - layout.bar_h() - y),
      ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Real robot")) {
    ImGui::End();
    return;
  }
  const auto& real = s.view().real;
  if (!real) {
    ImGui::TextDisabled("no state from the robot server yet");
  } else {
    const core::RobotState& st = real->state;
    ImGui::Text("%s, state age %.0f ms, gripper %.2f", to_string(st.mode),
                s.view().real_state_age_s * 1e3, st.gripper);
    if (ImGui::BeginTable("joints", 4, ImGuiTableFlags_SizingFixedFit)) {
      ImGui::TableSetupColumn("joint");
      ImGui::TableSetupColumn("value");
      ImGui::TableSetupColumn("to limit");
      ImGui::TableSetupColumn("ghost - real");
      ImGui::TableHeadersRow();
      for (int j = 0; j < model.dof() && j < st.q.size(); ++j) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(model.joint(j).name.c_str());
        ImGui::TableNextColumn();
        const char* unit = is_prismatic(model, j) ? "mm" : "deg";
        ImGui::Text("%8.2f %s", display_value(model, j, st.q[j]), unit);
        ImGui::TableNextColumn();
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(margin_colour(model, j, st.q[j])),
                           "%7.1f", display_value(model, j, limit_margin(model, j, st.q[j])));
        ImGui::TableNextColumn();
        ImGui::Text("%7.2f", display_value(model, j, s.ghost().q()[j] - st.q[j]));
      }
      ImGui::EndTable();
    }
    if (st.fault) ImGui::TextColored(ImVec4(1, 0.3f, 0.25f, 1), "fault: %s", st.fault->c_str());
  }

  section("Initialize (moves the robot)");
  const auto& named = model.named_configurations();
  if (!named.empty()) {
    ui.named_index = std::clamp(ui.named_index, 0, static_cast<int>(named.size()) - 1);
    ImGui::SetNextItemWidth(80);
    if (ImGui::BeginCombo("##named", named[ui.named_index].name.c_str())) {
      for (std::size_t i = 0; i < named.size(); ++i) {
        if (ImGui::Selectable(named[i].name.c_str(), static_cast<int>(i) == ui.named_index)) {
          ui.named_index = static_cast<int>(i);
        }
      }
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Button("Initialize##named")) {
      ctx.act({.kind = ActionKind::kRealInitialize, .text = named[ui.named_index].name});
    }
    ImGui::SameLine();
  }
  ImGui::SetNextItemWidth(170);
  ImGui::InputTextWithHint("##typed", "q1,...,q6 deg", ui.typed_configuration,
                           sizeof ui.typed_configuration);
  ImGui::SameLine();
  if (ImGui::Button("Initialize##typed")) {
    // The robot moves to these values: "2abc" is refused, not read as 2.
    const auto values = core::parse_number_list(ui.typed_configuration, "joint values");
    if (!values) {
      ui.last_message =
          std::string(to_string(ActionKind::kRealInitialize)) + ": " + values.error().message;
      ui.last_failed = true;
    } else {
      UiAction a{.kind = ActionKind::kRealInitialize};
      a.q.resize(static_cast<int>(values->size()));
      for (std::size_t j = 0; j < values->size(); ++j) {
        a.q[static_cast<int>(j)] = is_prismatic(model, static_cast<int>(j))
                                       ? (*values)[j] / 1000.0
                                       : core::radians_from_degrees((*values)[j]);
      }
      ctx.act(a);
    }
  }

  section("Direct jog (conventional mode: moves the robot now)");
  const double step = core::radians_from_degrees(ui.joint_step_deg);
  for (int j = 0; j < model.dof(); ++j) {
    ImGui::PushID(100 + j);
    char label[16];
    std::snprintf(label, sizeof label, "%d-", j + 1);
    if (ImGui::Button(label)) ctx.act({.kind = ActionKind::kRealJoint, .index = j, .value = -step});
    ImGui::SameLine();
    std::snprintf(label, sizeof label, "%d+", j + 1);
    if (ImGui::Button(label)) ctx.act({.kind = ActionKind::kRealJoint, .index = j, .value = step});
    ImGui::SameLine();
    ImGui::PopID();
  }
  ImGui::NewLine();
  ImGui::PushID("realcart");
  draw_cartesian_jog(ctx, ActionKind::kRealCartesian);
  ImGui::PopID();
  if (ImGui::Button("Open gripper")) ctx.act({.kind = ActionKind::kRealGripper, .value = 1.0});
  ImGui::SameLine();
  if (ImGui::Button("Close gripper")) ctx.act({.kind = ActionKind::kRealGripper, .value = 0.0});
  ImGui::SameLine();
  int target = static_cast<int>(ui.input_target);
  ImGui::Text("keys/pad drive:");
  ImGui::SameLine();
  ImGui::RadioButton("ghost", &target, 0);
  ImGui::SameLine();
  ImGui::RadioButton("real", &target, 1);
  ui.input_target = static_cast<InputTarget>(target);
  ImGui::End();
}

}  // namespace telear::console
