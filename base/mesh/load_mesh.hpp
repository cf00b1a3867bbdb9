#pragma once
// Load a triangle mesh from STL (binary or ASCII), OBJ or PLY through assimp.
#include <string>

#include "base/mesh/triangle_mesh.hpp"

namespace gw {

struct LoadMeshOptions {
  double scale = 1.0;  // multiply coordinates, e.g. 1000 for a mesh in metres -> mm
};

// Reads `path`, keeps triangles only, welds vertices that have exactly the same
// coordinates (STL repeats every vertex per face), then applies `scale`.
// Throws MeshError "<path>: <problem>" for a missing, empty, unreadable or
// truncated file, or a file with no triangles. Does not judge geometry:
// NaN coordinates and open surfaces are reported by validate_mesh().
TriangleMesh load_mesh(const std::string& path, const LoadMeshOptions& options = {});

}  // namespace gw

namespace gw {
struct MeshReport;

// load_mesh + validate_mesh: throws MeshError "<path>: <first error>" when the mesh
// is unusable (e.g. NaN coordinates); fills `report` (warnings included) if given.
TriangleMesh load_valid_mesh(const std::string& path, const LoadMeshOptions& options = {},
                             MeshReport* report = nullptr);
}  // namespace gw
