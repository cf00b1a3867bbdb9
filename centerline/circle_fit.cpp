#include "centerline/circle_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace gw {

bool kasa_circle_fit(const std::vector<Eigen::Vector2d>& hits, Eigen::Vector2d& centre, double& radius) {
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  for (const auto& h : hits) {
    const Eigen::Vector3d row(h.x(), h.y(), 1.0);
    AtA += row * row.transpose();
    Atb -= row * h.squaredNorm();
  }
  const Eigen::Vector3d s = AtA.ldlt().solve(Atb);
  centre = Eigen::Vector2d(-0.5 * s(0), -0.5 * s(1));
  const double r2 = centre.squaredNorm() - s(2);
  if (!(r2 > 0) || !centre.allFinite()) return false;
  radius = std::sqrt(r2);
  return true;
}

double arc_span(const std::vector<Eigen::Vector2d>& hits, const Eigen::Vector2d& centre) {
  std::vector<double> a;
  for (const auto& h : hits) a.push_back(std::atan2(h.y() - centre.y(), h.x() - centre.x()));
  std::sort(a.begin(), a.end());
  double gap = a.front() + 2.0 * M_PI - a.back();
  for (size_t i = 1; i < a.size(); ++i) gap = std::max(gap, a[i] - a[i - 1]);
  return 2.0 * M_PI - gap;
}

}  // namespace gw
