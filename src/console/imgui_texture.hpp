#pragma once
// Internal to console: a GL texture name as Dear ImGui's texture id (ImGui::Image), for the
// panels that draw textures, defined once.

#include <imgui.h>

#include <cstdint>

namespace telear::console {

inline ImTextureID texture(unsigned id) {
  return reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(id));
}

}  // namespace telear::console
