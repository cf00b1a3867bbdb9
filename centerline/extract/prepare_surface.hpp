#pragma once
// Make any vessel surface usable by mean-curvature-flow skeletonisation: one closed,
// outward-oriented triangle 2-manifold with a face size tied to the vessel radius.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/mesh/triangle_mesh.hpp"

namespace gw {

// An open boundary loop that was closed: an inlet/outlet of a clinical surface, so a
// terminal candidate.
struct SurfaceCap {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // centroid of the loop vertices
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // points out of the vessel
  double radius = 0.0;                                // mean distance of the loop to its centre
};

struct ClosedSurface {
  TriangleMesh mesh;               // closed, single component, outward normals
  std::vector<SurfaceCap> caps;    // one per capped hole
  int dropped_components = 0;      // smaller pieces that were removed
  double volume = 0.0, area = 0.0; // of `mesh`
  // Radius of a tube with the same volume/area ratio (V/A = r/2): the size remeshing
  // and every tolerance of the pipeline are tied to.
  double mean_radius() const { return area > 0 ? 2.0 * volume / area : 0.0; }
};

// Repairs the triangle soup (duplicate/degenerate faces, inconsistent orientation,
// non-manifold vertices), keeps the largest component, caps every hole (flat
// triangulation) and orients the normals outwards. Throws std::runtime_error
// "<problem>" when the result is still not a closed 2-manifold enclosing a volume.
ClosedSurface close_surface(const TriangleMesh& mesh);

// Isotropic remeshing of a closed surface to edges of about `edge_length`
// (`iterations` passes of split/collapse/flip/smooth). Keeps it closed.
TriangleMesh remesh_surface(const TriangleMesh& closed, double edge_length, int iterations = 3);

}  // namespace gw
