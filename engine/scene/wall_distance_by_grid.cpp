#include "engine/scene/wall_distance_by_grid.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gw {

WallDistance wall_distance_by_grid(const VesselScene& scene, const Eigen::Vector3d& p, double radius) {
  const TriangleGrid& g = *scene.grid;
  // Every triangle lies in the grid's box: a radius reaching its farthest corner holds them all.
  const Eigen::Vector3d far_corner =
      (p - g.origin).cwiseAbs().cwiseMax((g.origin + g.cell * g.dims.cast<double>() - p).cwiseAbs());
  const double all = far_corner.norm();
  double r = std::isfinite(radius) && radius > 0 ? 2 * radius : 1.0;
  thread_local std::vector<int> cand;
  for (;;) {
    triangles_near(scene, p, r, cand);
    WallDistance wd = wall_distance_among(scene, p, cand, r);
    if (wd.triangle >= 0 || r > all) return wd;
    r *= 2;
  }
}

}  // namespace gw
