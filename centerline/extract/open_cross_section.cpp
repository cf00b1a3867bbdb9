#include "centerline/extract/open_cross_section.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gw {
namespace {

// Kasa circle fit (least squares on x^2 + y^2 + D x + E y + F = 0). False when degenerate.
bool kasa_fit(const std::vector<Eigen::Vector2d>& hits, Eigen::Vector2d& c, double& r) {
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  for (const auto& h : hits) {
    const Eigen::Vector3d row(h.x(), h.y(), 1.0);
    AtA += row * row.transpose();
    Atb -= row * h.squaredNorm();
  }
  const Eigen::Vector3d s = AtA.ldlt().solve(Atb);
  c = Eigen::Vector2d(-0.5 * s(0), -0.5 * s(1));
  const double r2 = c.squaredNorm() - s(2);
  if (!(r2 > 0) || !c.allFinite()) return false;
  r = std::sqrt(r2);
  return true;
}

// Angle (rad) the points span around c: 2 pi minus the largest gap between consecutive angles.
double span_around(const std::vector<Eigen::Vector2d>& hits, const Eigen::Vector2d& c) {
  std::vector<double> a;
  for (const auto& h : hits) a.push_back(std::atan2(h.y() - c.y(), h.x() - c.x()));
  std::sort(a.begin(), a.end());
  double gap = a.front() + 2.0 * M_PI - a.back();
  for (size_t i = 1; i < a.size(); ++i) gap = std::max(gap, a[i] - a[i - 1]);
  return 2.0 * M_PI - gap;
}

}  // namespace

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
    if (hits.size() < kRays / 2 || !kasa_fit(hits, c, r)) return out;
    std::vector<Eigen::Vector2d> kept;
    for (const auto& h : hits)
      if ((h - c).norm() <= 1.15 * r) kept.push_back(h);
    if (kept.size() == hits.size()) break;
    hits = std::move(kept);
  }
  if (hits.size() < kRays / 2 || !kasa_fit(hits, c, r)) return out;
  double residual = 0.0;
  for (const auto& h : hits) residual = std::max(residual, std::abs((h - c).norm() - r));
  if (residual > 0.08 * r || span_around(hits, c) < 240.0 / 180.0 * M_PI) return out;
  out.tube = true;
  out.centre = p + c.x() * u + c.y() * v;
  out.radius = r;
  out.elongation = std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace gw
