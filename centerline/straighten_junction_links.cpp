#include "centerline/straighten_junction_links.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gw {

int straighten_junction_links(const SkeletonTree& tree, std::vector<RefinedBranch>& branches, double spacing) {
  const std::vector<int> degree = tree.degree();
  int straightened = 0;
  for (size_t i = 0; i < tree.chains.size(); ++i) {
    const SkeletonChain& c = tree.chains[i];
    RefinedBranch& b = branches[i];
    if (c.a == c.b || degree[c.a] < 3 || degree[c.b] < 3 || b.points.size() < 3 || b.radii.empty()) continue;
    const Eigen::Vector3d from = b.points.front(), to = b.points.back(), chord = to - from;
    const double largest = *std::max_element(b.radii.begin(), b.radii.end());
    if (chord.norm() >= 4.0 * largest || chord.norm() <= 0.0) continue;
    // Doubling back: steps against the chord and half as long again as it (a vessel between two
    // junctions within four radii is never that curved; an arch segment of 43 mm on a 12 mm aorta is 1.2).
    bool backwards = false;
    double length = 0.0;
    for (size_t k = 0; k + 1 < b.points.size(); ++k) {
      backwards = backwards || (b.points[k + 1] - b.points[k]).dot(chord) < 0.0;
      length += (b.points[k + 1] - b.points[k]).norm();
    }
    if (!backwards || length < 1.5 * chord.norm()) continue;
    const int steps = std::max(1, static_cast<int>(std::round(chord.norm() / spacing)));
    RefinedBranch straight;
    for (int j = 0; j <= steps; ++j) {
      const double t = static_cast<double>(j) / steps;
      straight.points.push_back(from + t * chord);
      straight.radii.push_back(b.radii[static_cast<size_t>(std::lround(t * static_cast<double>(b.radii.size() - 1)))]);
      straight.elongation.push_back(std::numeric_limits<double>::infinity());
    }
    b = std::move(straight);
    ++straightened;
  }
  return straightened;
}

}  // namespace gw
