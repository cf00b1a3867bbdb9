#pragma once
// CGAL 3D Alpha Wrapping of a triangle soup: the fallback that always gives one closed,
// outward-oriented 2-manifold, whatever the input's defects (non-manifold joins, holes that
// cannot be capped, overlapping pieces, self-intersections).
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

// Inputs: `soup` (any triangles; orientation, manifoldness and connectivity are irrelevant),
// `alpha` (radius of the carving ball, mm: passages narrower than about alpha are not entered, so
// it must stay below the smallest vessel radius, and holes narrower than it are closed) and
// `offset` (distance of the wrap outside the input, mm; > 0).
// Output: a closed 2-manifold enclosing the input at distance `offset`, normals outwards.
// Deterministic: one soup always gives one wrap (allocations in a private region, see
// deterministic_heap.hpp). Throws std::runtime_error when the parameters are not positive or the
// wrap is empty.
TriangleMesh alpha_wrap_surface(const TriangleMesh& soup, double alpha, double offset);

}  // namespace gw
