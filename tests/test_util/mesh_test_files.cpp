#include "test_util/mesh_test_files.hpp"

#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

namespace telear::test_files {
namespace {

void put_float(std::string& out, float v) {
  char b[4];
  std::memcpy(b, &v, 4);
  out.append(b, 4);
}

}  // namespace

std::string binary_stl_cube() {
  // Each face: outward normal and two counter-clockwise triangles.
  struct Face {
    float n[3];
    float c[4][3];
  };
  const Face faces[6] = {
      {{0, 0, -1}, {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}},
      {{0, 0, 1}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}},
      {{0, -1, 0}, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}},
      {{0, 1, 0}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}},
      {{-1, 0, 0}, {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}},
      {{1, 0, 0}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}},
  };
  std::string out(80, ' ');
  const std::uint32_t count = 12;
  out.append(reinterpret_cast<const char*>(&count), 4);
  for (const Face& f : faces) {
    const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& tri : tris) {
      for (float v : f.n) put_float(out, v);
      for (int k : tri) {
        for (float v : f.c[k]) put_float(out, v);
      }
      out.append(2, '\0');
    }
  }
  return out;
}

std::string ascii_stl_tetrahedron() {
  const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int tris[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::ostringstream s;
  s << "solid tetra\n";
  for (const auto& t : tris) {
    s << "facet normal 0 0 0\n outer loop\n";
    for (int k : t) s << "  vertex " << p[k][0] << ' ' << p[k][1] << ' ' << p[k][2] << '\n';
    s << " endloop\nendfacet\n";
  }
  s << "endsolid tetra\n";
  return s.str();
}

std::string obj_square(const std::string& mtl_name) {
  return "mtllib " + mtl_name +
         "\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
         "usemtl paint\n"
         "f 1 2 3 4\n";
}

std::string mtl_paint(const Eigen::Vector3f& kd) {
  std::ostringstream s;
  s << "newmtl paint\nKa 0 0 0\nKd " << kd.x() << ' ' << kd.y() << ' ' << kd.z() << "\n";
  return s.str();
}

std::string collada_triangle(const Eigen::Vector3f& t, const Eigen::Vector3f& kd) {
  std::ostringstream s;
  s << R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_effects>
    <effect id="paint-effect"><profile_COMMON><technique sid="common"><phong>
      <diffuse><color sid="diffuse">)"
    << kd.x() << ' ' << kd.y() << ' ' << kd.z() << R"( 1</color></diffuse>
    </phong></technique></profile_COMMON></effect>
  </library_effects>
  <library_materials>
    <material id="paint" name="paint"><instance_effect url="#paint-effect"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="tri" name="tri"><mesh>
      <source id="tri-pos">
        <float_array id="tri-pos-array" count="9">0 0 0 1 0 0 0 1 0</float_array>
        <technique_common><accessor source="#tri-pos-array" count="3" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
      <triangles material="paint" count="1">
        <input semantic="VERTEX" source="#tri-vtx" offset="0"/>
        <p>0 1 2</p>
      </triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene" name="scene">
      <node id="part" name="part">
        <translate>)"
    << t.x() << ' ' << t.y() << ' ' << t.z() << R"(</translate>
        <scale>2 2 2</scale>
        <instance_geometry url="#tri">
          <bind_material><technique_common>
            <instance_material symbol="paint" target="#paint"/>
          </technique_common></bind_material>
        </instance_geometry>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
  return s.str();
}

}  // namespace telear::test_files
