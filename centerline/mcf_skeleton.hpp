#pragma once
// Mean-curvature-flow skeleton (CGAL, Tagliasacchi et al. 2012) of a closed surface,
// as plain arrays: curve nodes, edges, and where each node's surface vertices lie.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "base/mesh/triangle_mesh.hpp"

namespace gw {

struct SkeletonNode {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     // where the flow left it (off-axis)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // mean of its surface vertices (noisy on fine skeletons)
  int surface_vertices = 0;                            // size of the correspondence
};

struct RawSkeleton {
  std::vector<SkeletonNode> nodes;
  std::vector<std::pair<int, int>> edges;
};

// Runs CGAL::extract_mean_curvature_flow_skeleton on `closed` (a closed 2-manifold;
// close_surface() + remesh_surface() make one). Throws std::runtime_error when the
// flow yields fewer than two nodes.
RawSkeleton mcf_skeleton(const TriangleMesh& closed);

}  // namespace gw
