#include "telear/geometry/mesh_file.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/DefaultIOSystem.h>
#include <Eigen/Geometry>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include "telear/core/number_format.hpp"
#include "telear/geometry/feature_edges.hpp"
#include "telear/geometry/mesh_file_check.hpp"

namespace telear::geometry {
namespace {

namespace fs = std::filesystem;

// assimp opens whatever a file names beside it (an OBJ's mtllib, a COLLADA image): a folder
// (fopen succeeds on one; the read then fails, and assimp 5.2.5 leaks the stream: a fuzzer
// finding) or a device such as /dev/zero (an endless read). It opens regular files only.
class RegularFilesOnly : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    std::error_code ec;
    if (file == nullptr || !fs::is_regular_file(file, ec)) return nullptr;
    return DefaultIOSystem::Open(file, mode);
  }
};

// Bounds on the magnitude of each axis of a <mesh scale> (validate()).
constexpr double kMinMeshScale = 1e-6;
constexpr double kMaxMeshScale = 1e3;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

Eigen::Matrix4f to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4f out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

// The material's own diffuse colour; none for assimp's stand-in default material.
std::optional<Eigen::Vector3f> material_colour(const aiScene& scene, unsigned index) {
  if (index >= scene.mNumMaterials) return std::nullopt;
  const aiMaterial* material = scene.mMaterials[index];
  aiString name;
  if (material->Get(AI_MATKEY_NAME, name) == AI_SUCCESS &&
      std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME) {
    return std::nullopt;
  }
  aiColor4D diffuse;
  if (material->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) != AI_SUCCESS) return std::nullopt;
  return Eigen::Vector3f(diffuse.r, diffuse.g, diffuse.b).cwiseMax(0.0f).cwiseMin(1.0f);
}

struct Builder {
  const aiScene& scene;
  const MeshLoadOptions& options;
  const std::string& path;
  core::Mesh mesh;
  std::optional<Error> error;

  void limit_error(const char* what, std::size_t count, std::size_t limit) {
    error = Error{"mesh file " + path + ": " + std::to_string(count) + " " + what +
                  " exceed the limit of " + std::to_string(limit)};
  }

  // Appends every mesh instanced by `node` and its children under T_parent.
  void add_node(const aiNode& node, const Eigen::Matrix4f& T_parent) {
    const Eigen::Matrix4f T = T_parent * to_eigen(node.mTransformation);
    for (unsigned k = 0; k < node.mNumMeshes && !error; ++k) {
      add_mesh(*scene.mMeshes[node.mMeshes[k]], T);
    }
    for (unsigned c = 0; c < node.mNumChildren && !error; ++c) add_node(*node.mChildren[c], T);
  }

  void add_mesh(const aiMesh& m, const Eigen::Matrix4f& T_node) {
    std::size_t triangles = 0;
    for (unsigned f = 0; f < m.mNumFaces; ++f) triangles += m.mFaces[f].mNumIndices == 3;
    if (triangles == 0) return;  // points or lines only: nothing to draw as a solid
    // Instancing can multiply a small file: count what is actually built.
    if (mesh.vertices.size() + m.mNumVertices > options.limits.max_vertices) {
      return limit_error("vertices", mesh.vertices.size() + m.mNumVertices,
                         options.limits.max_vertices);
    }
    if (mesh.triangle_count() + triangles > options.limits.max_triangles) {
      return limit_error("triangles", mesh.triangle_count() + triangles,
                         options.limits.max_triangles);
    }
    Eigen::Matrix3f S = options.scale.cast<float>().asDiagonal();
    const Eigen::Matrix3f A = S * T_node.topLeftCorner<3, 3>();
    const Eigen::Vector3f t = S * T_node.topRightCorner<3, 1>();
    const Eigen::Matrix3f N = A.inverse().transpose();
    const bool mirrored = A.determinant() < 0.0f;

    Eigen::Vector3f colour = kDefaultMeshColour;
    if (options.rgba) {
      colour = options.rgba->head<3>();
    } else if (auto c = material_colour(scene, m.mMaterialIndex)) {
      colour = *c;
    }
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D& p = m.mVertices[v];
      const Eigen::Vector3f position = A * Eigen::Vector3f(p.x, p.y, p.z) + t;
      Eigen::Vector3f normal = Eigen::Vector3f::Zero();
      if (m.mNormals) {
        const aiVector3D& n = m.mNormals[v];
        normal = N * Eigen::Vector3f(n.x, n.y, n.z);
      }
      const float length = normal.norm();
      normal = std::isfinite(length) && length > 1e-12f ? Eigen::Vector3f(normal / length)
                                                        : Eigen::Vector3f::Zero();
      mesh.add_vertex(position, normal, colour);
    }
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3) continue;
      const std::uint32_t a = base + face.mIndices[0], b = base + face.mIndices[1],
                          c = base + face.mIndices[2];
      if (mirrored) {
        mesh.triangles.insert(mesh.triangles.end(), {a, c, b});
      } else {
        mesh.triangles.insert(mesh.triangles.end(), {a, b, c});
      }
    }
  }
};

bool has_usable_normals(const aiMesh& m) {
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    const aiVector3D& n = m.mNormals[v];
    if (!(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) ||
        n.SquareLength() < 1e-12f) {
      return false;
    }
  }
  return true;
}

// Vertices whose normal is missing (a file's zero normal) take their face's normal.
void repair_normals(core::Mesh& mesh) {
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    core::MeshVertex* v[3];
    for (int k = 0; k < 3; ++k)
      v[k] = &mesh.vertices[mesh.triangles[t + static_cast<std::size_t>(k)]];
    const auto pos = [](const core::MeshVertex* x) {
      return Eigen::Vector3f(x->position[0], x->position[1], x->position[2]);
    };
    const Eigen::Vector3f n = (pos(v[1]) - pos(v[0])).cross(pos(v[2]) - pos(v[0]));
    if (n.norm() <= 0.0f) continue;
    const Eigen::Vector3f unit = n.normalized();
    for (core::MeshVertex* x : v) {
      if (x->normal[0] == 0.0f && x->normal[1] == 0.0f && x->normal[2] == 0.0f) {
        for (int k = 0; k < 3; ++k) x->normal[k] = unit[k];
      }
    }
  }
}

}  // namespace

Status MeshLoadOptions::validate() const {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(scale[k]) || scale[k] == 0.0) {
      return Error{"mesh scale must be finite and non-zero on every axis, got " +
                   std::to_string(scale[0]) + " " + std::to_string(scale[1]) + " " +
                   std::to_string(scale[2])};
    }
  }
  // Real scales convert units (0.001 for millimetres, 0.0254 for inches, 1000 for km at
  // most); beyond these bounds a <mesh scale> is hostile or mistyped, and the body it would
  // make (a 1 cm part scaled by 1e9 spans the Earth) breaks drawing and collision checks.
  for (int k = 0; k < 3; ++k) {
    if (std::abs(scale[k]) < kMinMeshScale || std::abs(scale[k]) > kMaxMeshScale) {
      return Error{"mesh scale " + core::format_number(scale[0]) + " " +
                   core::format_number(scale[1]) + " " + core::format_number(scale[2]) +
                   " is absurd: each axis must be within 1e-06 .. 1000 in magnitude"};
    }
  }
  if (!(feature_angle_deg >= 0.0 && feature_angle_deg <= 180.0)) {
    return Error{"feature_angle_deg must be in [0, 180], got " + std::to_string(feature_angle_deg)};
  }
  if (limits.max_file_bytes == 0 || limits.max_vertices == 0 || limits.max_triangles == 0) {
    return Error{"mesh limits (max_file_bytes, max_vertices, max_triangles) must be positive"};
  }
  return Status::Ok();
}

bool is_supported_mesh_extension(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".stl" || ext == ".dae" || ext == ".obj";
}

Result<core::Mesh> load_mesh_file(const std::string& path, const MeshLoadOptions& options) {
  if (Status s = options.validate(); !s)
    return Error{"mesh file " + path + ": " + s.error().message};
  if (!is_supported_mesh_extension(path)) {
    return Error{"mesh file " + path + ": unsupported format '" + lower_extension(path) +
                 "' (supported: .stl, .dae, .obj)"};
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return Error{"mesh file " + path + " does not exist"};
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec) return Error{"mesh file " + path + ": cannot read its size (" + ec.message() + ")"};
  if (bytes > options.limits.max_file_bytes) {
    return Error{"mesh file " + path + " is " + std::to_string(bytes) +
                 " bytes, over the limit of " + std::to_string(options.limits.max_file_bytes) +
                 " bytes"};
  }

  // The formats whose importers assimp 5.2.5 crashes or leaks on when malformed
  // (mesh_file_check.hpp): checked first.
  if (const std::string extension = lower_extension(path);
      extension == ".dae" || extension == ".stl" || extension == ".obj") {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (extension == ".dae") {
      if (Status s = check_collada_structure(text, path); !s) return s.error();
    } else if (extension == ".obj") {
      if (Status s = check_obj_structure(text, path); !s) return s.error();
    } else if (is_ascii_stl(text)) {
      if (Status s = check_ascii_stl_structure(text, path); !s) return s.error();
    }
  }

  Assimp::Importer importer;
  importer.SetIOHandler(new RegularFilesOnly);  // the importer owns it
  // URDF meshes are in the link frame: keep COLLADA's coordinates as written (header).
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE,
                            static_cast<float>(options.feature_angle_deg));
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_ValidateDataStructure);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    const std::string why = importer.GetErrorString();
    return Error{"mesh file " + path + " is not a readable mesh (" +
                 (why.empty() ? std::string("no scene") : why) + ")"};
  }
  // A file "without normals" includes one that writes zero normals (many STL exporters do):
  // drop those so that assimp generates them, then join duplicate vertices.
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    aiMesh* m = scene->mMeshes[k];
    if (m->mNormals && !has_usable_normals(*m)) {
      delete[] m->mNormals;
      m->mNormals = nullptr;
    }
  }
  scene =
      importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals);
  if (!scene)
    return Error{"mesh file " + path + " is not a readable mesh (" + importer.GetErrorString() +
                 ")"};
  // The raw counts, before instancing multiplies them.
  std::size_t vertices = 0;
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) vertices += scene->mMeshes[k]->mNumVertices;
  if (vertices > options.limits.max_vertices) {
    return Error{"mesh file " + path + ": " + std::to_string(vertices) +
                 " vertices exceed the limit of " + std::to_string(options.limits.max_vertices)};
  }

  Builder builder{*scene, options, path, {}, std::nullopt};
  builder.add_node(*scene->mRootNode, Eigen::Matrix4f::Identity());
  if (builder.error) return *builder.error;
  if (builder.mesh.triangles.empty()) return Error{"mesh file " + path + " holds no triangles"};
  // A NaN or infinite coordinate (a binary STL's float can be any bit pattern) has no place in
  // a body: every later step (welding, hulls, collisions) assumes finite positions.
  for (std::size_t i = 0; i < builder.mesh.vertices.size(); ++i) {
    const float* p = builder.mesh.vertices[i].position;
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return Error{"mesh file " + path + ": vertex " + std::to_string(i) +
                   " is not finite (NaN or infinite coordinates)"};
    }
  }
  repair_normals(builder.mesh);
  set_feature_edges(builder.mesh, options.feature_angle_deg);
  return std::move(builder.mesh);
}

}  // namespace telear::geometry
