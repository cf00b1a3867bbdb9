#include "centerline/merge_close_junctions.hpp"
#include "base/util/median.hpp"

#include <algorithm>
#include <limits>

namespace gw {

namespace {

// Median radius of branch `chain` over its first ~8 mm from junction `node` (16 points at 0.5 mm).
double radius_near(const SkeletonTree& tree, const std::vector<RefinedBranch>& refined, size_t chain, int node) {
  std::vector<double> r = refined[chain].radii;
  if (tree.chains[chain].a != node) std::reverse(r.begin(), r.end());
  r.resize(std::min<size_t>(r.size(), 16));
  return r.empty() ? 0.0 : median(r);
}

// Radius of the thinnest arm of junction `node` other than chain `skip`.
double thinnest_refined_arm(const SkeletonTree& tree, const std::vector<RefinedBranch>& refined, int node, size_t skip) {
  double thinnest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < tree.chains.size(); ++i)
    if (i != skip && (tree.chains[i].a == node || tree.chains[i].b == node))
      thinnest = std::min(thinnest, radius_near(tree, refined, i, node));
  return thinnest;
}

}  // namespace

bool merge_close_junctions(SkeletonTree& tree, const std::vector<Eigen::Vector3d>& recentred,
                           const std::vector<RefinedBranch>& refined, double factor) {
  const std::vector<int> degree = tree.degree();
  int best = -1;
  double best_ratio = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < tree.chains.size(); ++i) {
    const SkeletonChain& c = tree.chains[i];
    if (c.a == c.b || degree[c.a] < 3 || degree[c.b] < 3) continue;
    const double openings = thinnest_refined_arm(tree, refined, c.a, i) + thinnest_refined_arm(tree, refined, c.b, i);
    const double ratio = (recentred[c.a] - recentred[c.b]).norm() / openings;
    if (ratio < factor && ratio < best_ratio) {
      best = static_cast<int>(i);
      best_ratio = ratio;
    }
  }
  if (best < 0) return false;
  const SkeletonChain gone = tree.chains[static_cast<size_t>(best)];
  tree.chains.erase(tree.chains.begin() + best);
  const int keep = std::min(gone.a, gone.b), drop = std::max(gone.a, gone.b);
  const Eigen::Vector3d centre = 0.5 * (tree.nodes[static_cast<size_t>(gone.a)] + tree.nodes[static_cast<size_t>(gone.b)]);
  tree.nodes[static_cast<size_t>(keep)] = centre;
  tree.nodes.erase(tree.nodes.begin() + drop);
  for (SkeletonChain& c : tree.chains) {
    for (int* end : {&c.a, &c.b}) {
      if (*end == drop) *end = keep;
      else if (*end > drop) --*end;
    }
    if (c.a == keep) c.points.front() = centre;
    if (c.b == keep) c.points.back() = centre;
  }
  return true;
}

}  // namespace gw
