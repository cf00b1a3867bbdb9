#pragma once
// Merge vertices with bit-identical coordinates and re-index faces.
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

// Returns a mesh whose vertices are unique; faces keep their order and winding.
// Unreferenced vertices are dropped. Vertices are compared by bit pattern, so NaN
// coordinates weld only with the same NaN (validate_mesh reports them).
TriangleMesh weld_vertices(const TriangleMesh& mesh);

}  // namespace gw
