// Mesh files through assimp: counts, bounds after scale and node transforms, colours, the
// feature-edge wire-frame, the limits and every error message. The files are written here.

#include "telear/geometry/mesh_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "telear/geometry/feature_edges.hpp"
#include "test_util/mesh_test_files.hpp"

namespace telear::geometry {
namespace {

using ::testing::HasSubstr;
using namespace test_files;

Eigen::Vector3f position(const core::Mesh& m, std::uint32_t i) {
  const core::MeshVertex& v = m.vertices[i];
  return {v.position[0], v.position[1], v.position[2]};
}

Eigen::Vector3f colour(const core::Mesh& m, std::uint32_t i) {
  const core::MeshVertex& v = m.vertices[i];
  return {v.colour[0], v.colour[1], v.colour[2]};
}

Eigen::AlignedBox3f bounds(const core::Mesh& m) {
  Eigen::AlignedBox3f box;
  for (std::uint32_t i = 0; i < m.vertices.size(); ++i) box.extend(position(m, i));
  return box;
}

// Every triangle's winding normal points away from `centre` and agrees with its vertices'
// normals (the file's or the generated ones).
void expect_outward(const core::Mesh& m, const Eigen::Vector3f& centre) {
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const std::uint32_t* v = &m.triangles[3 * t];
    const Eigen::Vector3f a = position(m, v[0]), b = position(m, v[1]), c = position(m, v[2]);
    const Eigen::Vector3f n = (b - a).cross(c - a);
    EXPECT_GT(n.dot((a + b + c) / 3.0f - centre), 0.0f) << "triangle " << t;
    for (int k = 0; k < 3; ++k) {
      const core::MeshVertex& x = m.vertices[v[k]];
      const Eigen::Vector3f vn(x.normal[0], x.normal[1], x.normal[2]);
      EXPECT_NEAR(vn.norm(), 1.0f, 1e-4f);
      EXPECT_GT(vn.dot(n), 0.0f) << "triangle " << t << " vertex " << k;
    }
  }
}

TEST(MeshFileTest, BinaryStlCubeHasTwelveTrianglesTwelveFeatureEdgesAndDefaultGrey) {
  TempDir dir;
  const std::string path = dir.write("cube.stl", binary_stl_cube());
  auto mesh = load_mesh_file(path);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->triangle_count(), 12u);
  EXPECT_EQ(mesh->vertices.size(), 24u);  // 4 per face: corners shared within a flat face
  EXPECT_EQ(mesh->line_count(), 12u);     // the 6 face diagonals are flat: not drawn
  EXPECT_TRUE(bounds(*mesh).isApprox(
      Eigen::AlignedBox3f(Eigen::Vector3f::Zero(), Eigen::Vector3f::Ones())));
  expect_outward(*mesh, Eigen::Vector3f::Constant(0.5f));
  EXPECT_TRUE(colour(*mesh, 0).isApprox(kDefaultMeshColour));
}

TEST(MeshFileTest, ScaleStretchesTheBoundsAndAMirrorKeepsTheWindingOutward) {
  TempDir dir;
  const std::string path = dir.write("cube.stl", binary_stl_cube());
  MeshLoadOptions options;
  options.scale = {2.0, 3.0, 0.5};
  auto mesh = load_mesh_file(path, options);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_TRUE(bounds(*mesh).max().isApprox(Eigen::Vector3f(2.0f, 3.0f, 0.5f)));
  expect_outward(*mesh, Eigen::Vector3f(1.0f, 1.5f, 0.25f));

  options.scale = {-1.0, 1.0, 1.0};
  auto mirrored = load_mesh_file(path, options);
  ASSERT_TRUE(mirrored) << mirrored.error().message;
  EXPECT_TRUE(bounds(*mirrored).min().isApprox(Eigen::Vector3f(-1.0f, 0.0f, 0.0f)));
  expect_outward(*mirrored, Eigen::Vector3f(-0.5f, 0.5f, 0.5f));
}

TEST(MeshFileTest, UrdfRgbaOverridesTheDefaultColour) {
  TempDir dir;
  MeshLoadOptions options;
  options.rgba = Eigen::Vector4f(0.9f, 0.1f, 0.2f, 1.0f);
  auto mesh = load_mesh_file(dir.write("cube.stl", binary_stl_cube()), options);
  ASSERT_TRUE(mesh) << mesh.error().message;
  for (std::uint32_t i = 0; i < mesh->vertices.size(); ++i) {
    EXPECT_TRUE(colour(*mesh, i).isApprox(Eigen::Vector3f(0.9f, 0.1f, 0.2f)));
  }
}

TEST(MeshFileTest, AsciiStlWithoutNormalsGetsFlatOutwardNormals) {
  TempDir dir;
  auto mesh = load_mesh_file(dir.write("tetra.STL", ascii_stl_tetrahedron()));
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->triangle_count(), 4u);
  EXPECT_EQ(mesh->line_count(), 6u);  // every dihedral angle of this tetrahedron is > 30 deg
  expect_outward(*mesh, Eigen::Vector3f::Constant(0.25f));
}

TEST(MeshFileTest, ObjTakesItsMaterialColourUnlessTheUrdfGivesOne) {
  TempDir dir;
  dir.write("paint.mtl", mtl_paint({0.2f, 0.4f, 0.6f}));
  const std::string path = dir.write("square.obj", obj_square("paint.mtl"));
  auto mesh = load_mesh_file(path);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->triangle_count(), 2u);
  EXPECT_EQ(mesh->line_count(), 4u);  // the boundary; the diagonal is flat
  EXPECT_TRUE(colour(*mesh, 0).isApprox(Eigen::Vector3f(0.2f, 0.4f, 0.6f), 1e-5f));

  MeshLoadOptions options;
  options.rgba = Eigen::Vector4f(1.0f, 0.5f, 0.0f, 1.0f);
  auto painted = load_mesh_file(path, options);
  ASSERT_TRUE(painted) << painted.error().message;
  EXPECT_TRUE(colour(*painted, 0).isApprox(Eigen::Vector3f(1.0f, 0.5f, 0.0f)));
}

TEST(MeshFileTest, ColladaAppliesNodeTransformsAsWrittenAndItsMaterial) {
  TempDir dir;
  const Eigen::Vector3f t(0.1f, 0.2f, 0.3f);
  auto mesh = load_mesh_file(dir.write("tri.dae", collada_triangle(t, {0.8f, 0.3f, 0.1f})));
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->triangle_count(), 1u);
  // translate * scale(2): the unit triangle doubled, then moved; Z_UP is not turned to Y_UP.
  const Eigen::AlignedBox3f box = bounds(*mesh);
  EXPECT_TRUE(box.min().isApprox(t, 1e-5f)) << box.min().transpose();
  EXPECT_TRUE(box.max().isApprox(t + Eigen::Vector3f(2.0f, 2.0f, 0.0f), 1e-5f))
      << box.max().transpose();
  EXPECT_TRUE(colour(*mesh, 0).isApprox(Eigen::Vector3f(0.8f, 0.3f, 0.1f), 1e-5f));
}

TEST(MeshFileTest, FeatureEdgesFollowTheAngle) {
  // Two triangles folded by 20 deg along their shared edge: a crease only below 20 deg.
  core::Mesh m;
  const float a = 20.0f * static_cast<float>(M_PI) / 180.0f;
  const Eigen::Vector3f n(0, 0, 1), c(1, 1, 1);
  m.add_vertex({0, 0, 0}, n, c);
  m.add_vertex({1, 0, 0}, n, c);
  m.add_vertex({0, 1, 0}, n, c);
  m.add_vertex({-std::cos(a), 0, std::sin(a)}, n, c);
  m.triangles = {0, 1, 2, 0, 2, 3};
  set_feature_edges(m, 30.0);
  EXPECT_EQ(m.line_count(), 4u);  // the boundary only
  set_feature_edges(m, 10.0);
  EXPECT_EQ(m.line_count(), 5u);  // and the fold
}

TEST(MeshFileTest, AFileOverTheSizeLimitIsRefusedBeforeReading) {
  TempDir dir;
  const std::string path = dir.write("cube.stl", binary_stl_cube());
  MeshLoadOptions options;
  options.limits.max_file_bytes = 100;
  auto mesh = load_mesh_file(path, options);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message,
            "mesh file " + path + " is 684 bytes, over the limit of 100 bytes");
}

TEST(MeshFileTest, TooManyVerticesOrTrianglesNameTheCountAndLimit) {
  TempDir dir;
  const std::string path = dir.write("cube.stl", binary_stl_cube());
  MeshLoadOptions options;
  options.limits.max_vertices = 10;
  auto mesh = load_mesh_file(path, options);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message, "mesh file " + path + ": 24 vertices exceed the limit of 10");
  options.limits.max_vertices = 100;
  options.limits.max_triangles = 11;
  mesh = load_mesh_file(path, options);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message, "mesh file " + path + ": 12 triangles exceed the limit of 11");
}

TEST(MeshFileTest, MissingUnsupportedAndCorruptFilesAreErrors) {
  TempDir dir;
  const std::string missing = (dir.path() / "none.stl").string();
  auto mesh = load_mesh_file(missing);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message, "mesh file " + missing + " does not exist");

  const std::string ply = dir.write("part.3ds", "3ds");
  mesh = load_mesh_file(ply);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message,
            "mesh file " + ply + ": unsupported format '.3ds' (supported: .stl, .dae, .obj)");

  for (const auto& [name, text] : {std::pair<std::string, std::string>{"junk.stl", "no mesh"},
                                   {"junk.dae", "<COLLADA><library_geometries>"},
                                   {"empty.obj", ""}}) {
    const std::string path = dir.write(name, text);
    mesh = load_mesh_file(path);
    ASSERT_FALSE(mesh) << name;
    EXPECT_THAT(mesh.error().message, HasSubstr("mesh file " + path)) << name;
    EXPECT_THAT(mesh.error().message, ::testing::AnyOf(HasSubstr("is not a readable mesh"),
                                                       HasSubstr("holds no triangles")))
        << name;
  }
}

// Issue 25: assimp 5.2.5 dereferences a null pointer on a COLLADA primitive without inputs (the
// fuzzer's input, fuzz/crashes/mesh/collada_triangles_without_inputs.dae, crashed the program);
// telear checks the structure first and refuses the file with what is missing.
TEST(MeshFileTest, MalformedColladaIsRefusedBeforeAssimpReadsIt) {
  TempDir dir;
  const std::string mesh_open = "<COLLADA><library_geometries><geometry id=\"g\"><mesh>";
  const std::string mesh_close = "</mesh></geometry></library_geometries></COLLADA>";
  const std::string positions =
      "<source id=\"pos\"><float_array id=\"pa\" count=\"3\">0 0 0</float_array>"
      "<technique_common><accessor source=\"#pa\" count=\"1\" stride=\"3\"/>"
      "</technique_common></source><vertices id=\"v\"><input semantic=\"POSITION\" "
      "source=\"#pos\"/></vertices>";
  struct Case {
    std::string body, problem;
  };
  for (const Case& c : std::vector<Case>{
           {"<triangles count=\"1\"></triangles>", "<triangles> on line 1 has no VERTEX input"},
           {positions + "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\"/>"
                        "</triangles>",
            "<triangles> on line 1 has no index list <p>"},
           {positions + "<polylist count=\"1\"><input semantic=\"VERTEX\" source=\"#v\"/>"
                        "<p>0 0 0</p></polylist>",
            "<polylist> on line 1 has no <vcount>"},
           {positions + "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#nowhere\"/>"
                        "<p>0 0 0</p></triangles>",
            "<input> on line 1: source '#nowhere' names no element of the file"},
           {"<vertices id=\"v\"/>", "<vertices> on line 1 has no POSITION input"},
           // fuzz/crashes/mesh/collada_count_beyond_its_indices.dae: assimp spent 40 s on it.
           {positions + "<triangles count=\"2\"><input semantic=\"VERTEX\" source=\"#v\" "
                        "offset=\"0\"/><p>0 0 0</p></triangles>",
            "<triangles> on line 1: count 2 needs 6 indices, <p> holds 3"},
           {positions + "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\"/>"
                        "<p>0c0 0</p></triangles>",
            "<triangles> on line 1 has a <p> that is not a list of indices"},
           // fuzz/crashes/mesh/collada_scale_not_a_number.dae: assimp threw on "[2" and leaked
           // the scene.
           {positions + "<scale>[2 2 2</scale>", "<scale> on line 1 does not hold 3 numbers"},
           {positions + "<color>1 0 0 1 0</color>", "<color> on line 1 does not hold 4 numbers"},
           // fuzz/crashes/mesh/collada_instance_without_url.dae: assimp threw and leaked.
           {positions + "<instance_geometry erl=\"#g\"/>",
            "<instance_geometry> on line 1 has no url"},
       }) {
    const std::string path = dir.write("bad.dae", mesh_open + c.body + mesh_close);
    auto mesh = load_mesh_file(path);
    ASSERT_FALSE(mesh) << c.problem;
    EXPECT_EQ(mesh.error().message,
              "mesh file " + path + " is not a readable mesh (COLLADA: " + c.problem + ")");
  }
  // TinyXML 1 read past the text on a UTF-8 character cut by its end, inside an attribute
  // (fuzz/crashes/mesh/collada_utf8_cut_at_the_end.dae: a heap overflow): text that is not
  // UTF-8 is refused before it parses.
  const std::string cut_character =
      dir.write("cut_character.dae", "<COLLADA><scene><instance_visual_scene url=\"#a=u\xd7");
  auto mesh = load_mesh_file(cut_character);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message,
            "mesh file " + cut_character +
                " is not a readable mesh (COLLADA: not UTF-8 text, an invalid byte sequence at "
                "byte 48)");
  const std::string not_collada = dir.write("scene.dae", "<scene/>");
  mesh = load_mesh_file(not_collada);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message,
            "mesh file " + not_collada +
                " is not a readable mesh (COLLADA: the root element is not <COLLADA>)");
  const std::string cut = dir.write("cut.dae", "<COLLADA><library_geometries>");
  mesh = load_mesh_file(cut);
  ASSERT_FALSE(mesh);
  EXPECT_THAT(mesh.error().message, HasSubstr("(COLLADA: not well-formed XML: "));
}

// Issue 25: assimp 5.2.5 leaks the mesh of an ASCII STL cut inside a facet (the fuzzer's input,
// fuzz/crashes/mesh/stl_cut_inside_a_facet.stl); telear checks the grammar first.
TEST(MeshFileTest, MalformedAsciiStlIsRefusedBeforeAssimpReadsIt) {
  TempDir dir;
  const std::string facet =
      "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n"
      " endloop\nendfacet\n";
  struct Case {
    std::string text, problem;
  };
  for (const Case& c : std::vector<Case>{
           {"solid\nfacet normal", "line 2: expected 'facet normal X Y Z' or 'endsolid'"},
           // fuzz/crashes/mesh/stl_normal_not_in_lower_case.stl: assimp leaked the facets.
           {"solid\nfacet NORMAL 0 0 1\n", "line 2: expected 'facet normal X Y Z' or 'endsolid'"},
           // ... and so did "vertEx" (fuzz/crashes/mesh/stl_vertex_not_in_lower_case.stl):
           // assimp's tokens facet, vertex and endsolid are lower case.
           {"solid\nfacet normal 0 0 1\nouter loop\nvertEx 0 0 0\n",
            "line 4: expected 'vertex X Y Z'"},
           {"solid\nFacet normal 0 0 1\n", "line 2: expected 'facet normal X Y Z' or 'endsolid'"},
           {"solid cut\n" + facet.substr(0, 40), "line 4: expected 'vertex X Y Z'"},
           {"solid s\n" + facet, "line 9: expected 'endsolid' (the file ends inside a solid)"},
           {"solid s\nfacet normal 0 0 1\n outer loop\n  vertex 0 zero 0\n",
            "line 4: expected 'vertex X Y Z'"},
           // fuzz/crashes/mesh/stl_hexadecimal_number.stl: assimp leaked the facets read.
           {"solid s\nfacet normal 0 0 1\n outer loop\n  vertex 0x01 0 0\n",
            "line 4: expected 'vertex X Y Z'"},
           {"solid s\n" + facet + "endsolid s\nextra\n", "line 10: expected 'solid'"},
           {"solid s\nfacet normal 0 0 1\n outer loop\n  vertex 0" + std::string(1, '\0') +
                " 0 0\n",
            "line 4: a NUL byte in the text"},
           // assimp reads only spaces and tabs between words: a vertical tab before a number
           // leaked the facets read (fuzz/crashes/mesh/stl_vertical_tab_before_a_number.stl).
           {"solid s\nfacet normal 0 0 1\n outer loop\n  vertex \v0 0 0\n",
            "line 4: a control character (0x0B) in the text"},
       }) {
    const std::string path = dir.write("bad.stl", c.text);
    auto mesh = load_mesh_file(path);
    ASSERT_FALSE(mesh) << c.problem;
    EXPECT_EQ(mesh.error().message,
              "mesh file " + path + " is not a readable mesh (ASCII STL, " + c.problem + ")");
  }
  // Two solids in one file are ASCII STL as some exporters write it.
  const std::string two =
      dir.write("two.stl", "solid a\n" + facet + "endsolid a\nsolid b\n" + facet + "endsolid b\n");
  auto mesh = load_mesh_file(two);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->triangle_count(), 2u);
}

// Issue 25: a binary STL whose vertex is NaN (fuzz/crashes/mesh/stl_binary_nan_vertex.stl)
// reached the feature edges' welding grid, where converting NaN to an integer is undefined
// behaviour; such a mesh is refused.
TEST(MeshFileTest, ANonFiniteVertexIsRefused) {
  TempDir dir;
  std::string stl(80, ' ');
  const std::uint32_t facets = 1;
  stl.append(reinterpret_cast<const char*>(&facets), 4);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float facet[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, nan, 0};
  stl.append(reinterpret_cast<const char*>(facet), sizeof facet);
  stl.append(2, '\0');
  const std::string path = dir.write("nan.stl", stl);
  auto mesh = load_mesh_file(path);
  ASSERT_FALSE(mesh);
  EXPECT_THAT(mesh.error().message, HasSubstr("mesh file " + path + ": vertex "));
  EXPECT_THAT(mesh.error().message, HasSubstr(" is not finite (NaN or infinite coordinates)"));
}

// Issue 25: assimp opened whatever an OBJ's mtllib names -- a folder (it leaked the stream:
// fuzz/crashes/mesh/obj_mtllib_names_a_folder.obj) or /dev/zero (an endless read). Only
// regular files are opened; the mesh loads with its default colour.
TEST(MeshFileTest, AnObjReadsOnlyRegularFilesBesideIt) {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "folder");
  for (const std::string mtllib : {"folder/", "/dev/zero"}) {
    const std::string path =
        dir.write("part.obj", "mtllib " + mtllib + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    auto mesh = load_mesh_file(path);
    ASSERT_TRUE(mesh) << mtllib << ": " << mesh.error().message;
    EXPECT_EQ(mesh->triangle_count(), 1u) << mtllib;
  }
}

// Issue 25: assimp leaks the mesh of an OBJ whose face names a vertex the file lacks
// (fuzz/crashes/mesh/obj_face_beyond_its_vertices.obj), or that has a NUL byte; telear checks
// every index first.
TEST(MeshFileTest, AnObjIndexBeyondItsListsIsRefusedBeforeAssimpReadsIt) {
  TempDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n";
  struct Case {
    std::string text, problem;
  };
  for (const Case& c : std::vector<Case>{
           {"v 0 0 0\nf 1\no f3\nf 21\n", "line 2: a face needs three vertices"},
           {tri + "f 1 2 4\n", "line 5: '4' names no vertex of the file (3 defined)"},
           {tri + "f 1//1 2//2 3//1\n", "line 5: '2//2' names no normal of the file (1 defined)"},
           {tri + "f 1/1 2/1 3/1\n",
            "line 5: '1/1' names no texture coordinate of the file (0 defined)"},
           {tri + "f -1 -2 -4\n", "line 5: '-4' names no vertex of the file (3 defined)"},
           {tri + "f 1 2 x\n", "line 5: 'x' names no vertex of the file (3 defined)"},
           // assimp leaked the mesh of an OBJ with a NUL byte in it, read as the file's end
           // (fuzz/crashes/mesh/obj_nul_inside_a_statement.obj).
           {tri + "f 1 2" + std::string(1, '\0') + " 3\n", "line 5: a NUL byte in the text"},
           // assimp leaked the mesh of a vertex whose number ran into a Latin-1 space
           // (fuzz/crashes/mesh/obj_vertex_number_runs_into_a_byte.obj).
           {"v 0 0\xa0 0\n", "line 1: 'v' takes numbers, not '0\xa0'"},
           {"v 0 0x1 0\n", "line 1: 'v' takes numbers, not '0x1'"},
           {"v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 1: 'v' with 2 numbers"},
           {tri + "vn 0 0\n", "line 5: 'vn' with 2 numbers"},
           // assimp leaked the mesh of a face mixing 'v//vn' with '11/' and 'v'
           // (fuzz/crashes/mesh/obj_face_mixes_its_corners_forms.obj): one form per element,
           // and that form one of OBJ's four.
           {tri + "f 1//1 2/ 3\n", "line 5: '2/' is not v, v/vt, v//vn or v/vt/vn"},
           {tri + "f 1//1 2 3\n",
            "line 5: '2' is v where the first corner is v//vn (one form for "
            "every corner)"},
           {tri + "vt 0 0\nf 1/1/1 2//1 3/1/1\n",
            "line 6: '2//1' is v//vn where the first corner is v/vt/vn (one form for every "
            "corner)"},
           {tri + "vt 0 0\nf 1/1/ 2/1/ 3/1/\n", "line 6: '1/1/' is not v, v/vt, v//vn or v/vt/vn"},
           // assimp reads a statement by its word's first letter: "limitf ..." is a line to it,
           // and leaked the mesh (fuzz/crashes/mesh/obj_statement_read_by_its_first_letter.obj).
           {tri + "limitf 1 2 4\n", "line 5: '4' names no vertex of the file (3 defined)"},
           {tri + "vnormal 0 0\n", "line 5: 'vnormal' with 2 numbers"},
           // assimp's path filter ran past the end of a material library's name that ended
           // with "://" (fuzz/crashes/mesh/obj_mtllib_ends_with_a_url_scheme.obj).
           {"mtllib file://\n" + tri + "f 1 2 3\n",
            "line 1: 'mtllib' names a URL; a material library is a file beside the mesh"},
           {tri + "mtllib https://example.org/metal.mtl\n",
            "line 5: 'mtllib' names a URL; a material library is a file beside the mesh"},
           // assimp counts a vertex's numbers by their first character and did not count
           // ".0": the vertices after it were one short and it leaked the mesh of a face naming
           // the last (fuzz/crashes/mesh/obj_number_begins_with_its_point.obj).
           {"v 0 .5 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            "line 1: '.5' begins with its decimal point (write 0.5, as assimp counts numbers by "
            "a digit or sign)"},
           {tri + "vn 0 0 .1\n",
            "line 5: '.1' begins with its decimal point (write 0.1, as assimp counts numbers by "
            "a digit or sign)"},
       }) {
    const std::string path = dir.write("bad.obj", c.text);
    auto mesh = load_mesh_file(path);
    ASSERT_FALSE(mesh) << c.problem;
    EXPECT_EQ(mesh.error().message,
              "mesh file " + path + " is not a readable mesh (OBJ, " + c.problem + ")");
  }
  // Relative (negative) indices and v//vn corners within the lists load, and a comment may
  // end a vertex's line.
  ASSERT_TRUE(
      load_mesh_file(dir.write("commented.obj", "v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")));
  // A sign before the point is a number to assimp.
  ASSERT_TRUE(load_mesh_file(dir.write("signed.obj", "v 0 -.5 +.5\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")));
  auto mesh = load_mesh_file(dir.write("good.obj", tri + "f -3//1 -2//1 -1//1\n"));
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->triangle_count(), 1u);
}

TEST(MeshFileTest, InvalidOptionsNameTheField) {
  TempDir dir;
  MeshLoadOptions options;
  options.scale = {1.0, 0.0, 1.0};
  auto mesh = load_mesh_file(dir.write("cube.stl", binary_stl_cube()), options);
  ASSERT_FALSE(mesh);
  EXPECT_THAT(mesh.error().message, HasSubstr("mesh scale must be finite and non-zero"));
}

TEST(PrimitiveMeshTest, SphereCountsFollowTheFormulaAndAreWoundOutwards) {
  for (int n : {3, 8, 24}) {
    core::Mesh m;
    core::append_sphere(m, {0.1f, 0.2f, 0.3f}, 0.5f, n, {1, 1, 1});
    EXPECT_EQ(static_cast<int>(m.triangle_count()), core::sphere_triangle_count(n)) << n;
    EXPECT_EQ(static_cast<int>(m.line_count()), core::sphere_line_count(n)) << n;
    expect_outward(m, {0.1f, 0.2f, 0.3f});
  }
}

}  // namespace
}  // namespace telear::geometry
