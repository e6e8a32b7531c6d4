// Doors: a mesh file, as a URDF's <mesh filename="..."> hands it to telear
// (geometry::load_mesh_file: the size check, assimp's STL (binary and ASCII), Wavefront OBJ and
// COLLADA importers, telear's vertex and triangle limits, normals and feature edges), and a
// URDF with its mesh references resolved (geometry::load_robot_assets, as `--robot arm.urdf
// --package-path DIR` loads it: package://, file:// and relative paths, scales, materials,
// collision parts). assimp reads files, not memory, as telear calls it, so the input is
// written into a sandbox folder of this process's own (under $TMPDIR, removed at exit) with the
// extension the first byte picks (.stl, .obj, .dae, or .urdf); the sandbox also holds a valid
// mesh of each format (meshes/part.stl, .obj, .dae, also reachable as package://fuzz/...) for
// the URDFs to name, and files the input names beside it resolve inside it.

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_input.hpp"
#include "telear/geometry/mesh_file.hpp"
#include "telear/geometry/robot_assets.hpp"

namespace {

namespace fs = std::filesystem;

// A triangle in each format, for the URDFs to name.
constexpr const char* kStl =
    "solid part\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\n"
    "vertex 0 0.1 0\nendloop\nendfacet\nendsolid part\n";
constexpr const char* kObj = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nf 1 2 3\n";

void write(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

const fs::path& sandbox() {
  static const fs::path folder = [] {
    std::string pattern = (fs::temp_directory_path() / "telear_fuzz_mesh_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    const fs::path root(pattern);
    // package://fuzz/meshes/part.stl resolves through the package path root/.. + "fuzz".
    fs::create_directories(root / "fuzz" / "meshes");
    write(root / "fuzz" / "package.xml", "<package><name>fuzz</name></package>\n");
    write(root / "fuzz" / "meshes" / "part.stl", kStl);
    write(root / "fuzz" / "meshes" / "part.obj", kObj);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(sandbox(), ec);
    });
    return root;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  static const char* const kExtensions[] = {".stl", ".obj", ".dae", ".urdf"};
  const std::size_t door = fuzz::pick(data, size, 4);
  const fs::path path = sandbox() / "fuzz" / (std::string("input") + kExtensions[door]);
  write(path, fuzz::text(data, size));
  // Smaller limits than a robot's: a fuzzer's million-triangle mesh is no finding, only slow.
  geometry::MeshLimits limits;
  limits.max_vertices = 100'000;
  limits.max_triangles = 100'000;
  if (door < 3) {
    geometry::MeshLoadOptions options;
    options.limits = limits;
    (void)geometry::load_mesh_file(path.string(), options);
  } else {
    geometry::GeometryOptions options;
    options.package_paths = {sandbox().string()};
    options.ros_package_path = std::vector<std::string>{};  // not the machine's ROS packages
    options.limits = limits;
    (void)geometry::load_robot_assets({path.string(), "", {sandbox().string()}}, options);
  }
  return 0;
}
