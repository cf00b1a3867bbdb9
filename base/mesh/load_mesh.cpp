#include "base/mesh/load_mesh.hpp"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "base/mesh/validate_mesh.hpp"
#include "base/mesh/weld_vertices.hpp"

namespace gw {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw MeshError(path + ": " + problem);
}

// assimp's STL reader accepts a binary STL whose facet count does not match the file
// size in some versions; check the layout ourselves so a truncated file is never
// half-loaded. Binary STL: 80-byte header, uint32 count, 50 bytes per facet.
void check_binary_stl_size(const std::string& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  char head[5] = {};
  in.read(head, 5);
  if (std::string(head, 5) == "solid") return;  // ASCII STL (or a binary one whose header says "solid")
  if (size < 84) fail(path, "truncated binary STL (" + std::to_string(size) + " bytes, the header alone is 84)");
  in.seekg(80);
  unsigned char c[4];
  in.read(reinterpret_cast<char*>(c), 4);
  const std::uintmax_t facets = c[0] | (c[1] << 8) | (c[2] << 16) | (std::uintmax_t(c[3]) << 24);
  const std::uintmax_t expected = 84 + 50 * facets;
  if (size < expected)
    fail(path, "truncated binary STL (header announces " + std::to_string(facets) + " facets = " +
                   std::to_string(expected) + " bytes, file has " + std::to_string(size) + ")");
}

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

}  // namespace

TriangleMesh load_mesh(const std::string& path, const LoadMeshOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, "no such file");
  if (fs::is_directory(path, ec)) fail(path, "is a directory, not a mesh file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) fail(path, "cannot read file size (" + ec.message() + ")");
  if (size == 0) fail(path, "empty file");
  if (!std::ifstream(path).good()) fail(path, "cannot open file for reading");
  if (!(options.scale > 0.0) || !std::isfinite(options.scale))
    fail(path, "scale must be a positive finite number, got " + std::to_string(options.scale));

  const std::string ext = lowercase_extension(path);
  if (ext != ".stl" && ext != ".obj" && ext != ".ply")
    fail(path, "unsupported extension '" + ext + "' (expected .stl, .obj or .ply)");
  if (ext == ".stl") check_binary_stl_size(path, size);

  Assimp::Importer importer;
  // Only triangulate: welding is ours, and degenerate faces must reach validate_mesh
  // instead of being silently dropped by aiProcess_FindDegenerates.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene) fail(path, std::string("not a readable mesh (") + importer.GetErrorString() + ")");

  TriangleMesh raw;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int base = static_cast<int>(vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines are not surface
      faces.emplace_back(base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                         base + static_cast<int>(face.mIndices[2]));
    }
  }
  if (faces.empty()) fail(path, "contains no triangles");

  raw.V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (size_t i = 0; i < vertices.size(); ++i) raw.V.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  raw.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) raw.F.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();

  TriangleMesh mesh = weld_vertices(raw);
  mesh.V *= options.scale;
  return mesh;
}

}  // namespace gw

namespace gw {

TriangleMesh load_valid_mesh(const std::string& path, const LoadMeshOptions& options, MeshReport* report) {
  TriangleMesh mesh = load_mesh(path, options);
  MeshReport r = validate_mesh(mesh);
  if (!r.ok()) throw MeshError(path + ": " + r.errors.front());
  if (report) *report = std::move(r);
  return mesh;
}

}  // namespace gw
