#include "centerline/polyline_tools.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace gw {

std::vector<Eigen::Vector3d> smooth_polyline(std::vector<Eigen::Vector3d> p, int iterations) {
  for (int it = 0; it < iterations; ++it) {
    std::vector<Eigen::Vector3d> q = p;
    for (size_t i = 1; i + 1 < p.size(); ++i) q[i] = 0.25 * p[i - 1] + 0.5 * p[i] + 0.25 * p[i + 1];
    p.swap(q);
  }
  return p;
}

std::vector<Eigen::Vector3d> taubin_smooth_polyline(std::vector<Eigen::Vector3d> p, int iterations) {
  constexpr double kShrink = 0.5, kInflate = -0.53;  // Taubin (1995): pass band ~0.1 of the sampling rate
  for (int it = 0; it < iterations; ++it)
    for (double w : {kShrink, kInflate}) {
      std::vector<Eigen::Vector3d> q = p;
      for (size_t i = 1; i + 1 < p.size(); ++i) q[i] = p[i] + w * (0.5 * (p[i - 1] + p[i + 1]) - p[i]);
      p.swap(q);
    }
  return p;
}

void fit_line(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d& point, Eigen::Vector3d& direction) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& q : points) mean += q;
  mean /= double(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& q : points) cov += (q - mean) * (q - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  direction = eig.eigenvectors().col(2);
  if (direction.dot(points.back() - points.front()) < 0) direction = -direction;
  point = mean;
}

std::vector<Eigen::Vector3d> resample_polyline(const std::vector<Eigen::Vector3d>& p, double spacing) {
  if (p.size() < 2) return p;
  std::vector<double> s(p.size(), 0.0);
  for (size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
  const double total = s.back();
  const int n = std::max(1, static_cast<int>(std::round(total / spacing)));
  std::vector<Eigen::Vector3d> out{p.front()};
  size_t seg = 1;
  for (int k = 1; k < n; ++k) {
    const double target = total * k / n;
    while (seg + 1 < p.size() && s[seg] < target) ++seg;
    const double len = s[seg] - s[seg - 1];
    const double t = len > 0 ? std::clamp((target - s[seg - 1]) / len, 0.0, 1.0) : 0.0;
    out.push_back(p[seg - 1] + t * (p[seg] - p[seg - 1]));
  }
  out.push_back(p.back());
  return out;
}

std::vector<Eigen::Vector3d> polyline_tangents(const std::vector<Eigen::Vector3d>& p) {
  const size_t n = p.size();
  std::vector<Eigen::Vector3d> t(n, Eigen::Vector3d::UnitZ());
  if (n < 2) return t;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = p[std::min(i + 1, n - 1)] - p[i == 0 ? 0 : i - 1];
    if (d.norm() > 0) t[i] = d.normalized();
    else if (i > 0) t[i] = t[i - 1];
  }
  return t;
}

double interpolate_along(const std::vector<Eigen::Vector3d>& p, const std::vector<double>& v, double s) {
  if (p.empty()) return 0.0;
  double acc = 0.0;
  for (size_t i = 1; i < p.size(); ++i) {
    const double len = (p[i] - p[i - 1]).norm();
    if (acc + len >= s) {
      const double t = len > 0 ? std::clamp((s - acc) / len, 0.0, 1.0) : 0.0;
      return (1 - t) * v[i - 1] + t * v[i];
    }
    acc += len;
  }
  return v.back();
}

}  // namespace gw
