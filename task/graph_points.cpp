// graph_points (task/graph_motion.hpp).
// Input: a centerline graph. Output: its points in GraphMotion's order: the inlet, every branch's points
// (branch by branch), the bifurcation centres, the targets.
#include "task/graph_motion.hpp"

namespace gw {

std::vector<Eigen::Vector3d> graph_points(const CenterlineGraph& g) {
  std::vector<Eigen::Vector3d> out;
  out.push_back(g.inlet.position);
  for (const CenterlineBranch& b : g.branches) out.insert(out.end(), b.points.begin(), b.points.end());
  for (const Bifurcation& b : g.bifurcations) out.push_back(b.position);
  for (const Terminal& t : g.targets) out.push_back(t.position);
  return out;
}

}  // namespace gw
