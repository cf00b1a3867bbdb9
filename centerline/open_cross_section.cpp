#include "centerline/open_cross_section.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "centerline/circle_fit.hpp"

namespace gw {

CrossSection fit_open_cross_section(const VesselWall& wall, const Eigen::Vector3d& p, const Eigen::Vector3d& tangent,
                                    double max_length) {
  constexpr int kRays = 72;
  CrossSection out;
  out.centre = p;
  out.radius = wall.distance(p);
  const Eigen::Vector3d t = tangent.normalized();
  const Eigen::Vector3d u = t.unitOrthogonal(), v = t.cross(u);
  std::vector<Eigen::Vector2d> hits;
  for (int k = 0; k < kRays; ++k) {
    const double a = 2.0 * M_PI * k / kRays;
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    const double d = wall.ray_hit(p, dir.x() * u + dir.y() * v, max_length);
    if (d <= max_length) hits.push_back(d * dir);
  }
  Eigen::Vector2d c;
  double r = 0.0;
  for (int round = 0; round < 4; ++round) {
    if (hits.size() < kRays / 2 || !kasa_circle_fit(hits, c, r)) return out;
    std::vector<Eigen::Vector2d> kept;
    for (const auto& h : hits)
      if ((h - c).norm() <= 1.15 * r) kept.push_back(h);
    if (kept.size() == hits.size()) break;
    hits = std::move(kept);
  }
  if (hits.size() < kRays / 2 || !kasa_circle_fit(hits, c, r)) return out;
  double residual = 0.0;
  for (const auto& h : hits) residual = std::max(residual, std::abs((h - c).norm() - r));
  if (residual > 0.08 * r || arc_span(hits, c) < 240.0 / 180.0 * M_PI) return out;
  out.tube = true;
  out.centre = p + c.x() * u + c.y() * v;
  out.radius = r;
  out.elongation = std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace gw
