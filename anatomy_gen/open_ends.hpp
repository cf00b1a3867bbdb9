#pragma once
// Open the inlet and outlets of a capped vessel mesh, as segmented clinical meshes are.
#include <vector>

#include "anatomy_gen/tree_geometry.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

// Removes every face whose three vertices lie on one cap disc (within `tolerance` mm of
// its plane, inside its radius), then unreferenced vertices, and moves the hole borders
// onto the exact rim circles. Throws MeshError if a cap leaves no hole or the result is not
// one boundary loop per cap (manifold, one component, no degenerate face).
TriangleMesh remove_end_caps(const TriangleMesh& mesh, const std::vector<EndCap>& caps, double tolerance = 1e-3);

}  // namespace gw
