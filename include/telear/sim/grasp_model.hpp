#pragma once
// The simulator's pick-and-place box follows geometry's grasp model
// (telear/geometry/grasp_model.hpp): the one decision of when the gripper holds the box, shared
// by the simulated video, the session's plan validation and the robot server's collision guard
// (telear/geometry/carried_objects.hpp), which does not link the simulator.

#include "telear/geometry/grasp_model.hpp"

namespace telear::sim {

using GraspModel = geometry::GraspModel;
using GraspModelOptions = geometry::GraspModelOptions;

}  // namespace telear::sim
