#pragma once
// Internal to sim_rig: the ink and the paper of the simulated printed targets -- the calibration
// targets (calibration_targets.cpp) and the registration target on the flange
// (flange_target.cpp) -- one print, defined once.

#include <Eigen/Core>

namespace telear::sim {

inline const Eigen::Vector3f kBlack(0.04f, 0.04f, 0.045f);
inline const Eigen::Vector3f kWhite(0.93f, 0.93f, 0.92f);

}  // namespace telear::sim
