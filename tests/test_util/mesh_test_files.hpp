#pragma once
// Small mesh files written by the tests into a temporary directory (the project's own test
// data: a cube, a tetrahedron, a textured quad, a COLLADA triangle with a node transform).

#include <Eigen/Geometry>
#include <string>

#include "test_util/temp_dir.hpp"  // TempDir, which the mesh tests write these into

namespace telear::test_files {

// The unit cube [0, 1]^3 as a binary STL: 12 triangles with their face normals (684 bytes).
std::string binary_stl_cube();
// A tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1) as an ASCII STL: 4 triangles.
std::string ascii_stl_tetrahedron();
// One square [0, 1]^2 at z = 0 whose material `paint` (in `mtl_name`) has diffuse colour kd.
std::string obj_square(const std::string& mtl_name);
std::string mtl_paint(const Eigen::Vector3f& kd);
// One triangle (0,0,0) (1,0,0) (0,1,0) under a node translated by `t` and scaled by 2, with a
// material of diffuse colour kd; up_axis Z_UP.
std::string collada_triangle(const Eigen::Vector3f& t, const Eigen::Vector3f& kd);

}  // namespace telear::test_files
