#pragma once
// Checking a 4x4 matrix typed by a user (a CLI option, a file) before it is taken as a pose:
// why it is not a rigid transform, in words for the message. is_valid_rigid_transform
// (core/pose.hpp) answers only yes or no.

#include <Eigen/Core>
#include <string>

namespace telear::core {

// Why `T` is not a rigid transform (to `tolerance`), or "" when it is one, for messages such
// as "--T is not a rigid transform: <why>": "its last row is not 0 0 0 1", "its rotation block
// is not orthonormal (R R^T - I is off by 3; tolerance 0.0001)", "its rotation block is a
// reflection (determinant -1)". Entries are assumed finite.
std::string rigid_transform_problem(const Eigen::Matrix4d& T, double tolerance);

}  // namespace telear::core
