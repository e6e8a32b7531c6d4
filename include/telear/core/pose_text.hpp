#pragma once
// A tool pose as an operator writes it on one line (`telear kin ik --T` / `--pose`): 16
// numbers of a row-major 4x4, or x,y,z,roll,pitch,yaw. Untrusted text: a Result whose message
// names the option.

#include <Eigen/Geometry>
#include <string>

#include "telear/core/result.hpp"

namespace telear::core {

// 16 numbers, row-major, comma-separated or separated by blanks when there is no comma (as a
// printed matrix is copied). Printed matrices carry a few digits only: a rotation within 1e-4
// of orthonormal is accepted and re-orthonormalized. Errors: parse_number_list's, or
// "--T is not a rigid transform: <why>".
Result<Eigen::Isometry3d> rigid_transform_from_text(const std::string& text,
                                                    const std::string& option);

// "x,y,z,roll,pitch,yaw": metres, and radians or (with `degrees`) degrees, fixed axes x, y, z
// (core/pose.hpp). Errors: parse_number_list's, then " (x,y,z in m, roll,pitch,yaw in deg)".
Result<Eigen::Isometry3d> pose_from_text(const std::string& text, const std::string& option,
                                         bool degrees);

}  // namespace telear::core
