#include <imgui.h>

#include <algorithm>
#include <cstdint>

#include "telear/console/console_actions.hpp"
#include "telear/console/panels.hpp"
#include "telear/session/capture_session.hpp"

#include "imgui_texture.hpp"

namespace telear::console {

namespace {

const ImVec4 kGood(0.35f, 0.85f, 0.35f, 1);
const ImVec4 kBad(0.95f, 0.35f, 0.3f, 1);

void seen(bool yes) {
  ImGui::TextColored(yes ? kGood : kBad, "%s", yes ? "seen" : "not seen");
}

// The solution's fit of a pose ("pose N"), when it entered the solve.
const vision::ViewFit* fit_of(const session::CaptureSession& capture, int index) {
  if (!capture.solution()) return nullptr;
  const std::string name = "pose " + std::to_string(index);
  for (const vision::ViewFit& view : capture.solution()->result.views) {
    if (view.name == name) return &view;
  }
  return nullptr;
}

void draw_poses(const session::CaptureSession& capture, float height) {
  const ImGuiTableFlags flags =
      ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersInnerV;
  if (!ImGui::BeginTable("poses", 5, flags, ImVec2(0, height))) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("pose", ImGuiTableColumnFlags_WidthFixed, 40);
  ImGui::TableSetupColumn("frames", ImGuiTableColumnFlags_WidthFixed, 50);
  ImGui::TableSetupColumn("left", ImGuiTableColumnFlags_WidthFixed, 65);
  ImGui::TableSetupColumn("right", ImGuiTableColumnFlags_WidthFixed, 65);
  ImGui::TableSetupColumn("residual", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableHeadersRow();
  for (const session::CapturedPoseReport& pose : capture.poses()) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("%d", pose.index);
    ImGui::TableNextColumn();
    ImGui::Text("%d", pose.frames);
    ImGui::TableNextColumn();
    seen(pose.left_seen);
    ImGui::TableNextColumn();
    seen(pose.right_seen);
    ImGui::TableNextColumn();
    if (const vision::ViewFit* fit = fit_of(capture, pose.index)) {
      if (fit->dropped) {
        ImGui::TextColored(kBad, "%.2f px outlier", fit->rms_px);
      } else {
        ImGui::Text("%.2f px", fit->rms_px);
      }
    } else {
      ImGui::TextDisabled("-");
    }
  }
  if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);  // newest
  ImGui::EndTable();
}

void draw_result(const session::CaptureSession& capture) {
  if (!capture.last_solve_error().empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kBad);
    ImGui::TextWrapped("not solved: %s", capture.last_solve_error().c_str());
    ImGui::PopStyleColor();
    return;
  }
  if (!capture.solution()) {
    ImGui::TextDisabled("not solved yet: add poses (4 or more, turning the wrist), then Solve");
    return;
  }
  const vision::HandEyeResult& r = capture.solution()->result;
  ImGui::Text("base: +-%.2f mm  +-%.3f deg (1 sigma)   target on the flange: +-%.2f mm",
              r.base_sigma.position_mm, r.base_sigma.rotation_deg, r.target_sigma.position_mm);
  ImGui::Text("%d poses used, rms %.2f px left, %.2f px right", r.views_used, r.left.rms_px,
              r.right.rms_px);
  for (const std::string& note : r.notes) ImGui::TextColored(kBad, "%s", note.c_str());
  ImGui::TextDisabled("written with the poses: telear register --captures %s",
                      capture.directory().c_str());
}

}  // namespace

void draw_registration_panel(PanelContext& ctx, const PanelLayout& layout,
                             const CoverageTexture& coverage) {
  if (!ctx.ui.show_registration) return;
  session::Session& s = ctx.session;
  UiState& ui = ctx.ui;
  ImGui::SetNextWindowPos(ImVec2(0, layout.view_h()), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(
      ImVec2(layout.view_w(), layout.height - layout.bar_h() - layout.view_h()),
      ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(1.0f);  // it lies over the plan and status panels
  if (!ImGui::Begin("Registration", &ui.show_registration)) {
    ImGui::End();
    return;
  }
  const session::CaptureSession* capture = s.capture();
  // [SECTION] folder
  if (!capture) {
    ImGui::SetNextItemWidth(260);
    ImGui::InputText("##folder", ui.capture_folder, sizeof ui.capture_folder);
    ImGui::SameLine();
    if (ImGui::Button("Open capture")) {
      ctx.act(
          {.kind = ActionKind::kCaptureOpen, .text = ui.capture_folder, .spec = ui.capture_target});
    }
    ImGui::SetNextItemWidth(260);
    ImGui::InputTextWithHint("target##capture", "the robot's marker, or e.g. charuco:5x5:...",
                             ui.capture_target, sizeof ui.capture_target);
    ImGui::TextWrapped(
        "Register the cameras to the robot: open a new folder, jog the real arm (Real robot "
        "panel, or keys with 'real' selected) until both cameras see the flange's target, Add "
        "pose, and repeat over the images turning the wrist; then Solve.");
    ImGui::End();
    return;
  }
  ImGui::Text("capturing into %s", capture->directory().c_str());
  ImGui::SameLine();
  if (ImGui::SmallButton("Close")) ctx.act(simple(ActionKind::kCaptureClose));

  // [SECTION] buttons
  const bool idle = robot_idle(s);
  const bool adding = capture->adding();
  ImGui::BeginDisabled(adding);
  if (ImGui::Button(adding ? "Adding..." : "Add pose", ImVec2(110, 0))) {
    ctx.act(simple(ActionKind::kCaptureAdd));
  }
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Solve", ImVec2(80, 0))) ctx.act(simple(ActionKind::kCaptureSolve));
  ImGui::SameLine();
  const vision::CaptureObservations& detected = capture->detected();
  ImGui::Text("%zu poses, %s in %d left / %d right", capture->poses().size(),
              capture->target().is_board() ? "board" : "marker", detected.left_found,
              detected.right_found);
  if (adding || !idle) {
    ImGui::SameLine();
    ImGui::TextColored(
        ImVec4(0.9f, 0.7f, 0.2f, 1), "%s",
        adding ? "(adding: waits for the arm to rest)" : "(arm moving: added at rest)");
  } else if (!capture->last_add_error().empty()) {
    ImGui::TextColored(kBad, "not added: %s", capture->last_add_error().c_str());
  }

  // [SECTION] poses | coverage
  const float avail_w = ImGui::GetContentRegionAvail().x;
  const float avail_h = ImGui::GetContentRegionAvail().y;
  const float table_w = std::min(340.0f, avail_w * 0.4f);
  ImGui::BeginChild("##poses", ImVec2(table_w, avail_h), false);
  draw_poses(*capture, std::max(60.0f, avail_h));
  ImGui::EndChild();
  ImGui::SameLine();
  ImGui::BeginChild("##coverage", ImVec2(0, avail_h), false);
  const float result_h = ImGui::GetTextLineHeightWithSpacing() * 4.5f;
  if (coverage.id != 0 && coverage.width > 0 && coverage.height > 0) {
    const float w = ImGui::GetContentRegionAvail().x;
    const float h = std::max(20.0f, ImGui::GetContentRegionAvail().y - result_h);
    const float scale = std::min(w / coverage.width, h / coverage.height);
    ImGui::Image(texture(coverage.id), ImVec2(coverage.width * scale, coverage.height * scale));
  }
  draw_result(*capture);
  ImGui::EndChild();
  ImGui::End();
}

}  // namespace telear::console
