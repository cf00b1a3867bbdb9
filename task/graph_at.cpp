// graph_at (task/graph_motion.hpp).
// Inputs: the rest graph, its moving scene, its GraphMotion, a time t [s]. Output: `out`, the graph at t:
// each point X mapped to X + D(X, t) with the wall's own field (rigid, cardiac), or to X plus the weighted
// displacement of its rest vertices at t (phase surfaces).
#include <stdexcept>

#include "engine/scene/wall_motion.hpp"
#include "task/graph_motion.hpp"

namespace gw {

void graph_at(const CenterlineGraph& rest, const VesselScene& scene, const GraphMotion& gm, double t,
              CenterlineGraph& out) {
  if (!scene.motion) throw std::invalid_argument("graph_at: the scene's wall does not move");
  const WallMotion& m = *scene.motion;
  if (out.branches.size() != rest.branches.size() || out.bifurcations.size() != rest.bifurcations.size() ||
      out.targets.size() != rest.targets.size())
    out = rest;
  const bool by_vertices = m.kind == WallMotionKind::phases;
  const WallTime at = wall_time(m, t);
  int i = 0;
  auto map = [&](const Eigen::Vector3d& X, Eigen::Vector3d& x) {
    if (!by_vertices) {
      wall_field_position(m, X, t, x);
    } else {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      for (int j = gm.begin[static_cast<size_t>(i)]; j < gm.begin[static_cast<size_t>(i) + 1]; ++j) {
        const int v = gm.vertex[static_cast<size_t>(j)];
        d += gm.weight[static_cast<size_t>(j)] *
             (wall_vertex_position(m, scene.mesh, v, at) - scene.mesh.V.row(v).transpose());
      }
      x = X + d;
    }
    ++i;
  };
  map(rest.inlet.position, out.inlet.position);
  for (size_t b = 0; b < rest.branches.size(); ++b)
    for (size_t k = 0; k < rest.branches[b].points.size(); ++k) map(rest.branches[b].points[k], out.branches[b].points[k]);
  for (size_t b = 0; b < rest.bifurcations.size(); ++b) map(rest.bifurcations[b].position, out.bifurcations[b].position);
  for (size_t k = 0; k < rest.targets.size(); ++k) map(rest.targets[k].position, out.targets[k].position);
  if (i != gm.points) throw std::invalid_argument("graph_at: the GraphMotion was built for another graph");
}

}  // namespace gw
