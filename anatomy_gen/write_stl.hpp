#pragma once
// Binary STL writer: deterministic bytes (fixed header, float32 little-endian), so a
// regenerated anatomy is byte-identical to the committed one.
#include <string>

#include "base/mesh/triangle_mesh.hpp"

namespace gw {

// Writes `mesh` to `path` (via a temporary file, renamed at the end: never half a file).
// `header` (at most 80 characters) names the content. Throws MeshError on I/O failure.
void write_stl(const TriangleMesh& mesh, const std::string& path, const std::string& header);

}  // namespace gw
