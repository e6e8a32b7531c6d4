#include "telear/console/mouse_input.hpp"

#include <imgui.h>

namespace telear::console {

std::vector<InputIncrement> MouseInput::poll(double /*dt*/, const InputSteps& steps) {
  std::vector<InputIncrement> out;
  if (!over_view_) return out;
  const ImGuiIO& io = ImGui::GetIO();
  InputIncrement inc;
  inc.kind = InputIncrement::Kind::kCartesian;
  inc.frame = steps.frame;
  if (ImGui::IsMouseDown(ImGuiMouseButton_Right)) {
    inc.dX.y() = -io.MouseDelta.x / kPixelsPerStep * steps.cartesian_m;
    inc.dX.z() = -io.MouseDelta.y / kPixelsPerStep * steps.cartesian_m;
  }
  inc.dX.x() = io.MouseWheel * steps.cartesian_m;
  if (!inc.dX.isZero()) out.push_back(inc);
  return out;
}

}  // namespace telear::console
