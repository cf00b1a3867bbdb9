// make_graph_motion (task/graph_motion.hpp).
// Inputs: the rest centerline graph and its moving scene. Output: the point count and, for phase surfaces,
// each point's nearest rest vertices with inverse-distance weights (brute force, once per anatomy).
#include <algorithm>
#include <stdexcept>
#include <utility>

#include "engine/scene/wall_motion.hpp"
#include "task/graph_motion.hpp"

namespace gw {

GraphMotion make_graph_motion(const CenterlineGraph& rest, const VesselScene& scene) {
  if (!scene.motion) throw std::invalid_argument("make_graph_motion: the scene's wall does not move");
  const std::vector<Eigen::Vector3d> points = graph_points(rest);
  GraphMotion gm;
  gm.points = static_cast<int>(points.size());
  if (scene.motion->kind != WallMotionKind::phases) return gm;
  const Eigen::Index nv = scene.mesh.V.rows();
  const int k = static_cast<int>(std::min<Eigen::Index>(kGraphMotionVertices, nv));
  std::vector<std::pair<double, int>> by_distance(static_cast<size_t>(nv));
  gm.begin.push_back(0);
  for (const Eigen::Vector3d& p : points) {
    for (Eigen::Index v = 0; v < nv; ++v)
      by_distance[static_cast<size_t>(v)] = {(scene.mesh.V.row(v).transpose() - p).norm(), static_cast<int>(v)};
    std::partial_sort(by_distance.begin(), by_distance.begin() + k, by_distance.end());
    if (by_distance[0].first == 0.0) {  // on a vertex: that vertex's motion, exactly
      gm.vertex.push_back(by_distance[0].second);
      gm.weight.push_back(1.0);
    } else {
      double sum = 0;
      for (int j = 0; j < k; ++j) sum += 1.0 / by_distance[static_cast<size_t>(j)].first;
      for (int j = 0; j < k; ++j) {
        gm.vertex.push_back(by_distance[static_cast<size_t>(j)].second);
        gm.weight.push_back(1.0 / by_distance[static_cast<size_t>(j)].first / sum);
      }
    }
    gm.begin.push_back(static_cast<int>(gm.vertex.size()));
  }
  return gm;
}

}  // namespace gw
