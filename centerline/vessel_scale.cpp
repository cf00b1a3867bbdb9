#include "centerline/vessel_scale.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "centerline/vessel_wall.hpp"

namespace gw {

VesselScale estimate_vessel_scale(const TriangleMesh& surface, int samples) {
  const Eigen::Index nf = surface.F.rows();
  if (nf == 0) throw std::runtime_error("the surface has no faces to measure the vessel size on");
  std::vector<double> cumulative(static_cast<size_t>(nf));
  double total = 0.0;
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0)), b = surface.V.row(surface.F(f, 1)),
                          c = surface.V.row(surface.F(f, 2));
    total += 0.5 * (b - a).cross(c - a).norm();
    cumulative[static_cast<size_t>(f)] = total;
  }
  if (!(total > 0)) throw std::runtime_error("the surface has zero area");
  const VesselWall wall(surface);
  // Stratified by area: the k-th sample is the face holding the (k + 1/2)/n-th fraction of the area.
  std::vector<double> radii;  // one per ray that met the opposite wall
  const double bbox = (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm();
  Eigen::Index last = -1;
  for (int k = 0; k < samples; ++k) {
    const double at = (k + 0.5) / samples * total;
    const auto f = static_cast<Eigen::Index>(std::lower_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin());
    if (f >= nf || f == last) continue;
    last = f;
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0)), b = surface.V.row(surface.F(f, 1)),
                          c = surface.V.row(surface.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (!(n.norm() > 0)) continue;
    const Eigen::Vector3d inward = -n.normalized();
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    const double gap = 1e-6 * bbox;
    const double hit = wall.ray_hit(centre + gap * inward, inward, bbox);
    if (std::isfinite(hit) && hit > 0) radii.push_back(0.5 * (hit + gap));
  }
  if (radii.empty()) throw std::runtime_error("no inward ray meets the opposite wall: the surface encloses no lumen");
  std::sort(radii.begin(), radii.end());
  auto percentile = [&](double q) {
    return radii[std::min(radii.size() - 1, static_cast<size_t>(q * static_cast<double>(radii.size())))];
  };
  VesselScale s;
  s.small_radius = percentile(0.10);
  s.median_radius = percentile(0.50);
  s.samples = static_cast<int>(radii.size());
  return s;
}

}  // namespace gw
