#pragma once
// Mesh the implicit surface of a vessel tree with CGAL Mesh_3 (Delaunay refinement).
#include "anatomy_gen/tree_geometry.hpp"
#include "anatomy_gen/tube_field.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

// Returns the closed, 2-manifold surface of `field` (faces counter-clockwise seen from
// outside). Triangle size follows the local radius: edge ~ geometry.edge_per_radius x r.
// Refinement starts from seed points on every branch, so no thin branch is missed.
// Deterministic: the same geometry gives the same mesh, vertex for vertex.
TriangleMesh mesh_tree_surface(const TreeGeometry& geometry, const TubeField& field);

}  // namespace gw
