#include <imgui.h>

#include <algorithm>

#include "telear/console/console_actions.hpp"
#include "telear/console/panels.hpp"

namespace telear::console {

void draw_plan_panel(PanelContext& ctx, const PanelLayout& layout) {
  session::Session& s = ctx.session;
  UiState& ui = ctx.ui;
  const session::Plan& plan = s.plan();
  const float w = layout.view_w() * 0.5f;
  ImGui::SetNextWindowPos(ImVec2(0, layout.view_h()), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(w, layout.height - layout.bar_h() - layout.view_h()),
                           ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Plan")) {
    ImGui::End();
    return;
  }
  // [SECTION] recording
  ImGui::SetNextItemWidth(60);
  ImGui::InputFloat("s##dur", &ui.waypoint_duration_s, 0, 0, "%.1f");
  ui.waypoint_duration_s = std::clamp(ui.waypoint_duration_s, 0.0f, 60.0f);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110);
  ImGui::InputTextWithHint("##label", "label", ui.waypoint_label, sizeof ui.waypoint_label);
  ImGui::SameLine();
  if (ImGui::Button("Add ghost pose")) {
    ctx.act(
        {.kind = ActionKind::kPlanAdd, .value = ui.waypoint_duration_s, .text = ui.waypoint_label});
  }
  ImGui::SameLine();
  if (ImGui::Button("Clear")) ctx.act(simple(ActionKind::kPlanClear));

  // [SECTION] waypoints
  ui.selected_waypoint = std::min(ui.selected_waypoint, static_cast<int>(plan.size()) - 1);
  const float list_h = std::max(60.0f, ImGui::GetContentRegionAvail().y - 150);
  if (ImGui::BeginTable(
          "waypoints", 4,
          ImGuiTableFlags_ScrollY | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersOuter,
          ImVec2(0, list_h))) {
    ImGui::TableSetupColumn("#", ImGuiTableColumnFlags_WidthFixed, 24);
    ImGui::TableSetupColumn("label");
    ImGui::TableSetupColumn("min s", ImGuiTableColumnFlags_WidthFixed, 50);
    ImGui::TableSetupColumn("gripper", ImGuiTableColumnFlags_WidthFixed, 60);
    ImGui::TableHeadersRow();
    const int reached = s.preview() ? s.preview()->current().waypoint : -1;
    for (std::size_t i = 0; i < plan.size(); ++i) {
      const session::PlanWaypoint& wp = plan.waypoint(i);
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      char id[32];
      std::snprintf(id, sizeof id, "%zu%s", i + 1, static_cast<int>(i) == reached ? "*" : "");
      if (ImGui::Selectable(id, ui.selected_waypoint == static_cast<int>(i),
                            ImGuiSelectableFlags_SpanAllColumns)) {
        ui.selected_waypoint = static_cast<int>(i);
      }
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(wp.label.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.1f", wp.min_duration);
      ImGui::TableNextColumn();
      if (wp.gripper) {
        ImGui::Text("%.2f", *wp.gripper);
      } else {
        ImGui::TextDisabled("-");
      }
    }
    ImGui::EndTable();
  }
  const int sel = ui.selected_waypoint;
  ImGui::BeginDisabled(sel < 0);
  if (ImGui::Button("Delete")) ctx.act({.kind = ActionKind::kPlanDelete, .index = sel});
  ImGui::SameLine();
  if (ImGui::Button("Up") && sel > 0) {
    ctx.act({.kind = ActionKind::kPlanMove, .index = sel, .index2 = sel - 1});
    --ui.selected_waypoint;
  }
  ImGui::SameLine();
  if (ImGui::Button("Down") && sel >= 0 && sel + 1 < static_cast<int>(plan.size())) {
    ctx.act({.kind = ActionKind::kPlanMove, .index = sel, .index2 = sel + 1});
    ++ui.selected_waypoint;
  }
  ImGui::SameLine();
  if (ImGui::Button("Set duration")) {
    ctx.act({.kind = ActionKind::kPlanDuration, .index = sel, .value = ui.waypoint_duration_s});
  }
  ImGui::EndDisabled();

  // [SECTION] preview
  session::PlanPreview* preview = s.preview();
  if (ImGui::Button(preview && preview->playing() ? "Pause" : "Preview")) {
    ctx.act(simple(preview && preview->playing() ? ActionKind::kPreviewPause
                                                 : ActionKind::kPreviewPlay));
  }
  ImGui::SameLine();
  if (ImGui::Button("Stop")) ctx.act(simple(ActionKind::kPreviewStop));
  ImGui::SameLine();
  float t = preview ? static_cast<float>(preview->time()) : 0.0f;
  const float duration = preview ? static_cast<float>(preview->duration()) : 0.0f;
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderFloat("##scrub", &t, 0.0f, std::max(duration, 0.001f), "%.2f s") && preview) {
    ctx.act({.kind = ActionKind::kPreviewSeek, .value = t});
  }

  // [SECTION] validate, execute
  if (ImGui::Button("Validate")) ctx.act(simple(ActionKind::kValidate));
  ImGui::SameLine();
  ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.15f, 0.45f, 0.2f, 1));
  if (ImGui::Button("Execute")) ctx.act(simple(ActionKind::kExecute));
  ImGui::PopStyleColor();
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) ctx.act(simple(ActionKind::kCancel));
  ImGui::SameLine();
  ImGui::TextWrapped("%s", ui.validation_text.c_str());
  if (!ui.validation_collision.empty()) {
    ImGui::TextColored(
        ui.validation_collision_free ? ImVec4(0.6f, 0.9f, 0.6f, 1) : ImVec4(1.0f, 0.3f, 0.3f, 1),
        "%s", ui.validation_collision.c_str());
  }
  if (const session::ExecutionMonitor* monitor = s.monitor()) {
    const session::TrackingStatus& st = monitor->status();
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "%.0f %%  (%.2f / %.2f s)", st.progress * 100,
                  st.plan_time, monitor->trajectory().duration());
    ImGui::ProgressBar(static_cast<float>(st.progress), ImVec2(-1, 0), overlay);
    ImGui::Text("tracking error: now %.2f mrad, max %.2f mrad (joint %d), rms %.2f mrad",
                st.max_abs_error * 1e3, st.max_error_so_far * 1e3, st.max_error_joint + 1,
                st.rms_error * 1e3);
  }
  if (!s.last_execution_result().empty())
    ImGui::TextWrapped("last execution: %s", s.last_execution_result().c_str());
  // The plan is the message: the hash of the trajectory the preview showed and the robot
  // server's hash of what it ran (docs/trajectory.md); equal means the robot ran the preview.
  if (!s.previewed_hash().empty() || !s.executed_hash().empty()) {
    const std::string previewed = s.previewed_hash().substr(0, 12);
    const std::string executed = s.executed_hash().substr(0, 12);
    ImGui::Text("plan hash: previewed %s", previewed.empty() ? "-" : previewed.c_str());
    if (!executed.empty()) {
      ImGui::SameLine();
      const bool same = s.executed_hash() == s.previewed_hash();
      ImGui::TextColored(same ? ImVec4(0.4f, 0.9f, 0.4f, 1) : ImVec4(1.0f, 0.7f, 0.2f, 1),
                         "executed %s (%s)", executed.c_str(),
                         same ? "as previewed" : "not the last preview");
    }
  }
  ImGui::End();
}

}  // namespace telear::console
