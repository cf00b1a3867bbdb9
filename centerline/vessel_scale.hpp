#pragma once
// The local size of a vessel surface before it is closed: half the distance across the lumen,
// measured by rays cast inwards from points spread over the wall (a shape-diameter estimate).
// It sets the scale of every repair that needs one (alpha wrapping's ball and offset).
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

struct VesselScale {
  double small_radius = 0.0;   // 10th percentile of the local radii, area-weighted (the thin vessels)
  double median_radius = 0.0;  // 50th percentile
  int samples = 0;             // rays that hit the opposite wall
};

// Inputs: `surface`, triangles whose normals point out of the lumen (a soup is fine: faces are
// only intersected), `samples` points chosen deterministically in proportion to area.
// Each ray starts at a face centroid and runs along the inward normal; its first hit past a tiny
// gap is the diameter there (exact for a round tube, whose normals pass through the axis).
// Output: percentiles of half those distances. Throws std::runtime_error when no ray hits.
VesselScale estimate_vessel_scale(const TriangleMesh& surface, int samples = 1500);

}  // namespace gw
