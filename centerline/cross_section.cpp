#include "centerline/cross_section.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace gw {

CrossSection fit_cross_section(const VesselWall& wall, const Eigen::Vector3d& p, const Eigen::Vector3d& tangent,
                               double max_length, int rays, double wall_noise) {
  CrossSection out;
  out.centre = p;
  const Eigen::Vector3d t = tangent.normalized();
  const Eigen::Vector3d u = t.unitOrthogonal(), v = t.cross(u);
  std::vector<Eigen::Vector2d> hits;
  for (int k = 0; k < rays; ++k) {
    const double a = 2.0 * M_PI * k / rays;
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    const double d = wall.ray_hit(p, dir.x() * u + dir.y() * v, max_length);
    if (!(d <= max_length)) {
      out.radius = wall.distance(p);
      return out;
    }
    hits.push_back(d * dir);
  }
  // Kasa circle fit: x^2 + y^2 + D x + E y + F = 0 in least squares, through the 3x3
  // normal equations (fixed size: no dynamic-size Eigen kernels needed).
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  for (const auto& h : hits) {
    const Eigen::Vector3d row(h.x(), h.y(), 1.0);
    AtA += row * row.transpose();
    Atb -= row * h.squaredNorm();
  }
  const Eigen::Vector3d s = AtA.ldlt().solve(Atb);
  const Eigen::Vector2d c(-0.5 * s(0), -0.5 * s(1));
  const double r2 = c.squaredNorm() - s(2);
  if (!(r2 > 0)) {
    out.radius = wall.distance(p);
    return out;
  }
  const double r = std::sqrt(r2);
  double residual = 0.0, nearest = std::numeric_limits<double>::infinity(), farthest = 0.0, squares = 0.0;
  Eigen::Matrix3d oval_AtA = Eigen::Matrix3d::Zero();  // distance from the centre = r0 + A cos 2a + B sin 2a
  Eigen::Vector3d oval_Atb = Eigen::Vector3d::Zero();
  for (const auto& h : hits) {
    const double d = (h - c).norm();
    residual = std::max(residual, std::abs(d - r));
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
    squares += (d - r) * (d - r);
    if (wall_noise > 0) {  // only a rough wall's sections are judged by their oval (below)
      const double a = std::atan2(h.y() - c.y(), h.x() - c.x());
      const Eigen::Vector3d row(1.0, std::cos(2 * a), std::sin(2 * a));
      oval_AtA += row * row.transpose();
      oval_Atb += row * d;
    }
  }
  out.roughness = std::sqrt(squares / static_cast<double>(hits.size())) / r;
  out.centre = p + c.x() * u + c.y() * v;
  out.radius = r;
  // Judged from the fitted centre, not from `p`: a point far off-axis in a round tube
  // still sees a round section, which is exactly what re-centring must fix.
  out.elongation = nearest > 0 ? farthest / nearest : std::numeric_limits<double>::infinity();
  out.tube = out.elongation < 1.4 && residual < 0.1 * r;
  if (wall_noise > 0) {
    const Eigen::Vector3d oval = oval_AtA.ldlt().solve(oval_Atb);
    const double amplitude = oval.tail<2>().norm();
    out.elongation = amplitude < oval(0) ? (oval(0) + amplitude) / (oval(0) - amplitude)
                                         : std::numeric_limits<double>::infinity();
    out.tube = out.elongation < 1.4 && out.roughness < 0.1 && residual < (0.1 + 4.0 * wall_noise) * r;
  }
  if (!out.tube) {
    out.centre = p;
    out.radius = wall.distance(p);
  }
  return out;
}

}  // namespace gw
