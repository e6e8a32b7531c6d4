// rigid_transform_problem: why a user's 4x4 matrix is not a pose, in words.

#include "telear/core/rigid_transform.hpp"

#include <gtest/gtest.h>

namespace telear::core {
namespace {

TEST(RigidTransformProblem, SaysWhatIsWrongOrNothing) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T(0, 3) = 0.5;
  EXPECT_EQ(rigid_transform_problem(T, 1e-4), "");
  Eigen::Matrix4d last_row = T;
  last_row(3, 2) = 1.0;
  EXPECT_EQ(rigid_transform_problem(last_row, 1e-4), "its last row is not 0 0 0 1");
  Eigen::Matrix4d stretched = T;
  stretched(1, 1) = 2.0;
  EXPECT_EQ(rigid_transform_problem(stretched, 1e-4),
            "its rotation block is not orthonormal (R R^T - I is off by 3; tolerance 0.0001)");
  Eigen::Matrix4d mirrored = T;
  mirrored(2, 2) = -1.0;
  EXPECT_EQ(rigid_transform_problem(mirrored, 1e-4),
            "its rotation block is a reflection (determinant -1)");
}

}  // namespace
}  // namespace telear::core
