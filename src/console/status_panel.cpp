#include <imgui.h>

#include "telear/console/console_actions.hpp"
#include "telear/console/panels.hpp"

namespace telear::console {

namespace {
void latency_row(const char* name, const session::LatencySummary& l) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(name);
  ImGui::TableNextColumn();
  ImGui::Text("%.2f", l.p50_s * 1e3);
  ImGui::TableNextColumn();
  ImGui::Text("%.2f", l.p99_s * 1e3);
}

void eye_row(const char* name, const session::EyeResidual& r) {
  if (r.valid()) {
    ImGui::Text("overlay error %s: %.2f px rms, %.2f px max", name, r.rms_px, r.max_px);
  } else {
    ImGui::TextDisabled("overlay error %s: %s", name,
                        r.message.empty() ? "not measured" : r.message.c_str());
  }
}
}  // namespace

void draw_status_panel(PanelContext& ctx, const PanelLayout& layout) {
  session::Session& s = ctx.session;
  const float w = layout.view_w() * 0.5f;
  ImGui::SetNextWindowPos(ImVec2(w, layout.view_h()), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(w, layout.height - layout.bar_h() - layout.view_h()),
                           ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Status")) {
    ImGui::End();
    return;
  }
  const session::SessionStats st = s.stats();
  ImGui::Text("video %.1f fps, console %.1f fps, frame age %.0f ms", st.video_fps, ctx.ui.fps,
              st.frame_age_s * 1e3);
  ImGui::Text("robot state age %.1f ms, round trip %.2f ms", st.robot_state_age_s * 1e3,
              st.robot_round_trip_s * 1e3);
  ImGui::Text("video %.0f kB/s, commands sent %llu B", st.video_bytes_per_s / 1e3,
              static_cast<unsigned long long>(st.command_bytes_sent));
  eye_row("left ", st.residual.left);
  eye_row("right", st.residual.right);
  ImGui::Text("AR->VR %d, VR->AR %d switches", s.display().ar_to_vr_switches(),
              s.display().vr_to_ar_switches());
  if (ImGui::BeginTable("latency", 3, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg)) {
    ImGui::TableSetupColumn("stage");
    ImGui::TableSetupColumn("p50 ms");
    ImGui::TableSetupColumn("p99 ms");
    ImGui::TableHeadersRow();
    for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) {
      latency_row(net::kLatencyStages[i].label, st.latency[i]);
    }
    ImGui::EndTable();
  }
  // Glass to glass: the frame code read back from the drawn eye (docs/latency.md); it needs a
  // stamping source and the raw video at its own size.
  if (st.shown.samples > 0) {
    ImGui::Text("capture -> shown p50 %.1f ms, p99 %.1f ms (frame code)", st.shown.p50_s * 1e3,
                st.shown.p99_s * 1e3);
  } else if (st.shown_without_code > 0) {
    ImGui::TextDisabled("capture -> shown: not measured: no frame code");
  } else {
    ImGui::TextDisabled("capture -> shown: not measured: no video shown");
  }
  ImGui::Separator();
  ImGui::BeginChild("events", ImVec2(0, 0), false);
  const auto& events = s.events();
  for (auto it = events.rbegin(); it != events.rend(); ++it) {
    const ImVec4 colour =
        it->kind == session::SessionEvent::Kind::kError     ? ImVec4(1, 0.4f, 0.35f, 1)
        : it->kind == session::SessionEvent::Kind::kWarning ? ImVec4(1, 0.75f, 0.3f, 1)
                                                            : ImVec4(0.8f, 0.8f, 0.8f, 1);
    ImGui::TextColored(colour, "%7.2f  %s", it->time, it->message.c_str());
  }
  ImGui::EndChild();
  ImGui::End();
}

}  // namespace telear::console
