#include "telear/console/ui_state.hpp"

namespace telear::console {

namespace {
constexpr std::pair<ViewLayout, const char*> kLayouts[] = {
    {ViewLayout::kSideBySide, "sbs"},    {ViewLayout::kTopBottom, "tb"},
    {ViewLayout::kAnaglyph, "anaglyph"}, {ViewLayout::kLeftEye, "left"},
    {ViewLayout::kRightEye, "right"},    {ViewLayout::kSeparate, "separate"},
    {ViewLayout::kPageFlip, "page-flip"}};
}  // namespace

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
