#include "telear/console/ui_state.hpp"

namespace telear::console {

namespace {
constexpr std::pair<ViewLayout, const char*> kLayouts[] = {
    {ViewLayout::kSideBySide, "sbs"},    {ViewLayout::kTopBottom, "tb"},
    {ViewLayout::kAnaglyph, "anaglyph"}, {ViewLayout::kLeftEye, "left"},
    {ViewLayout::kRightEye, "right"},    {ViewLayout::kSeparate, "separate"},
    {ViewLayout::kPageFlip, "page-flip"}};
}  // namespace

render::ArViewOptions with_view_settings(render::ArViewOptions options, const UiState& ui) {
  options.ghost_style =
      ui.wireframe ? render::DrawOptions::Style::kWireframe : render::DrawOptions::Style::kSolid;
  options.ghost_alpha = ui.ghost_opacity;
  options.show_reported_ghost = ui.show_reported;
  options.show_predicted = ui.show_predicted;
  options.show_capture_arm = ui.show_capture_arm;
  options.overlay_mode =
      ui.undistorted ? render::OverlayMode::kUndistorted : render::OverlayMode::kRaw;
  return options;
}

const char* layout_name(ViewLayout layout) {
  for (const auto& [l, name] : kLayouts) {
    if (l == layout) return name;
  }
  return "?";
}

std::optional<ViewLayout> parse_layout(const std::string& name) {
  for (const auto& [l, n] : kLayouts) {
    if (name == n) return l;
  }
  return std::nullopt;
}

}  // namespace telear::console
