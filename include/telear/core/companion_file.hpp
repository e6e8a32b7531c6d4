#pragma once
// A robot's companion files (its body, NAME.body.yaml; its registration marker,
// NAME.marker.yaml): found beside the robot's own file first, so a robot loaded from a
// folder of its own brings them along, then in the data directory's robots/ folder, where the
// shipped robots keep theirs.

#include <string>

#include "telear/core/robot_model.hpp"

namespace telear::core {

// The path of NAME<suffix> (suffix e.g. ".body.yaml"), or "" when there is none.
std::string find_companion_file(const RobotModel& model, const std::string& suffix);

// Where shipped companion files live: <data>/robots.
std::string companion_directory();

}  // namespace telear::core
