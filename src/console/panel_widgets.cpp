#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "telear/console/panels.hpp"
#include "telear/core/angles.hpp"

namespace telear::console {

void section(const char* title) {
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextDisabled("%s", title);
}

bool is_prismatic(const core::RobotModel& model, int joint) {
  return model.joint(joint).type == core::JointType::kPrismatic;
}

double display_value(const core::RobotModel& model, int joint, double q) {
  return is_prismatic(model, joint) ? q * 1000.0 : core::degrees_from_radians(q);
}

double limit_margin(const core::RobotModel& model, int joint, double q) {
  const core::JointLimits& l = model.joint(joint).limits;
  return std::min(q - l.lower, l.upper - q);
}

unsigned margin_colour(const core::RobotModel& model, int joint, double q) {
  const core::JointLimits& l = model.joint(joint).limits;
  const double fraction = limit_margin(model, joint, q) / std::max(1e-9, l.upper - l.lower);
  // Red within 2 % of the range from a limit, amber within 10 %, green otherwise.
  if (fraction < 0.02) return IM_COL32(235, 70, 60, 255);
  if (fraction < 0.10) return IM_COL32(240, 180, 40, 255);
  return IM_COL32(90, 200, 90, 255);
}

}  // namespace telear::console
