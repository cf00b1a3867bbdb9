#pragma once
// Voxel staircase: a surface made by marching cubes from a binary label map (ITK-SNAP's export, a
// script's skimage.measure.marching_cubes) has its faces in the lattice's few orientations, and
// steps of half a voxel that break every round-section fit of the centerline. Detected here and
// smoothed away with Taubin's lambda|mu filter (no shrinkage of the tube, unlike plain Laplacian).
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

// Share of the surface area whose normal is a voxel-lattice direction: an axis, a face diagonal
// (0,1,1)/sqrt2 or a space diagonal (1,1,1)/sqrt3, within 0.03 (|sorted |n| - lattice|), in the
// mesh's own axes. Marching cubes of a binary mask: 0.9-1.0; smooth surfaces: about 0.01.
double lattice_area_share(const TriangleMesh& mesh);

// Taubin smoothing (Taubin 1995): `passes` pairs of uniform-Laplacian steps, +lambda then -mu.
// lambda 0.5, mu 0.53: pass band 0.11, so the half-voxel steps go and the vessel's shape stays.
// Connectivity is unchanged; positions only.
TriangleMesh taubin_smooth(const TriangleMesh& mesh, int passes, double lambda = 0.5, double mu = 0.53);

}  // namespace gw
