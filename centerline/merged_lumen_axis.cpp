#include "centerline/merged_lumen_axis.hpp"
#include "centerline/circle_fit.hpp"
#include "centerline/polyline_tools.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace gw {
namespace {

// Centre (in the plane) of the circle of known radius r nearest to the hits in least squares:
// Gauss-Newton on sum (|h - c| - r)^2 from c = 0. A known radius makes an arc of ~90 deg enough.
bool fit_known_radius(const std::vector<Eigen::Vector2d>& hits, double r, Eigen::Vector2d& c, double& residual) {
  c.setZero();
  for (int it = 0; it < 20; ++it) {
    Eigen::Matrix2d JtJ = Eigen::Matrix2d::Zero();
    Eigen::Vector2d Jtr = Eigen::Vector2d::Zero();
    for (const auto& h : hits) {
      const Eigen::Vector2d d = c - h;
      const double n = d.norm();
      if (n < 1e-12) return false;
      const Eigen::Vector2d J = d / n;  // d(|c - h| - r)/dc
      JtJ += J * J.transpose();
      Jtr += J * (n - r);
    }
    if (JtJ.determinant() < 1e-9 * hits.size() * hits.size()) return false;
    const Eigen::Vector2d delta = -JtJ.inverse() * Jtr;
    c += delta;
    if (delta.norm() < 1e-7 * r) break;
  }
  residual = 0.0;
  for (const auto& h : hits) residual = std::max(residual, std::abs((h - c).norm() - r));
  return c.allFinite();
}

// Circle with free radius (Gauss-Newton on centre and radius from c, r): for arcs wide enough to
// measure the radius, which changes along a tapering branch.
bool fit_free_radius(const std::vector<Eigen::Vector2d>& hits, Eigen::Vector2d& c, double& r, double& residual) {
  for (int it = 0; it < 20; ++it) {
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (const auto& h : hits) {
      const Eigen::Vector2d d = c - h;
      const double n = d.norm();
      if (n < 1e-12) return false;
      const Eigen::Vector3d J(d.x() / n, d.y() / n, -1.0);
      JtJ += J * J.transpose();
      Jtr += J * (n - r);
    }
    const Eigen::Vector3d delta = -JtJ.ldlt().solve(Jtr);
    if (!delta.allFinite()) return false;
    c += delta.head<2>();
    r += delta.z();
    if (delta.norm() < 1e-7 * std::abs(r)) break;
  }
  residual = 0.0;
  for (const auto& h : hits) residual = std::max(residual, std::abs((h - c).norm() - r));
  return c.allFinite() && r > 0;
}

}  // namespace

MergedLumenAxis trace_merged_lumen_axis(const VesselWall& wall, const Eigen::Vector3d& point,
                                        const Eigen::Vector3d& direction, double radius,
                                        const MergedLumenQuery& query, double step, double reach,
                                        double wall_noise) {
  MergedLumenAxis out;
  constexpr int kRays = 72;
  Eigen::Vector3d p0 = point, d = direction.normalized();
  // Two passes: the second casts its rays from the axis the first recovered.
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Eigen::Vector3d> centres;
    std::vector<double> radii;
    const Eigen::Vector3d u = d.unitOrthogonal(), v = d.cross(u);
    const double far = (point - p0).dot(d);  // every pass starts level with the clean-tube point
    double r = radius;                        // follows the branch's taper while arcs are wide
    int misses = 0;
    for (double s = 0.0; s <= reach * radius && misses < 4; s += step) {
      if (!centres.empty()) ++misses;  // reset below when this station gives a centre
      const Eigen::Vector3d origin = p0 + (far - s) * d;
      if (query.at_junction(origin)) break;
      std::vector<Eigen::Vector2d> hits;
      for (int k = 0; k < kRays; ++k) {
        const double a = 2.0 * M_PI * k / kRays;
        const Eigen::Vector3d ray = std::cos(a) * u + std::sin(a) * v;
        const double t = wall.ray_hit(origin, ray, 2.0 * radius);
        if (!(t <= 2.0 * radius)) continue;
        if (query.own_wall(origin + t * ray)) hits.emplace_back(t * std::cos(a), t * std::sin(a));
      }
      if (hits.size() < 8) continue;
      Eigen::Vector2d c;
      double residual = 0.0;
      if (!fit_known_radius(hits, r, c, residual)) continue;
      if (arc_span(hits, c) > 250.0 / 180.0 * M_PI) {
        double free_r = r;
        Eigen::Vector2d free_c = c;
        double free_residual = 0.0;
        if (fit_free_radius(hits, free_c, free_r, free_residual) && std::abs(free_r - r) < 0.3 * r)
          c = free_c, r = free_r, residual = free_residual;
      }
      const double stray = wall_noise > 0 ? (0.08 + 3.0 * wall_noise) * r : 0.08 * r;
      if (c.norm() > 0.75 * r || residual > stray || arc_span(hits, c) < 0.5 * M_PI) continue;
      centres.push_back(origin + c.x() * u + c.y() * v);
      radii.push_back(r);
      misses = 0;
    }
    // The branch is straight for a few radii from the junction and then often curves away: fit
    // the axis over the 3.5 radii nearest the junction only.
    std::vector<Eigen::Vector3d> all = centres;
    std::vector<double> all_radii = radii;
    while (centres.size() > 4 && (centres.front() - centres.back()).norm() > 3.5 * radius) centres.erase(centres.begin());
    if (centres.size() < 4) return out;
    Eigen::Vector3d mean, axis;
    fit_line(centres, mean, axis);
    if (axis.dot(d) < 0) axis = -axis;
    const double span = (centres.front() - centres.back()).norm();
    if (span < 1.5 * radius || axis.dot(d) < std::cos(0.3)) return out;  // too short, or off by > 17 deg
    p0 = mean;
    d = axis;
    std::reverse(all.begin(), all.end());  // nearest the junction first
    std::reverse(all_radii.begin(), all_radii.end());
    out.centres = std::move(all);
    out.radii = std::move(all_radii);
  }
  out.ok = true;
  out.point = p0;
  out.direction = d;
  return out;
}

}  // namespace gw
