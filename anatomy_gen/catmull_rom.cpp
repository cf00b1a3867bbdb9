#include "anatomy_gen/catmull_rom.hpp"

#include <algorithm>
#include <cmath>

namespace gw {

Eigen::Vector3d catmull_rom_point(const std::vector<Eigen::Vector3d>& c, double u) {
  const int n = static_cast<int>(c.size());
  if (n == 1) return c[0];
  int i = static_cast<int>(std::floor(u));
  i = std::clamp(i, 0, n - 2);
  const double t = std::clamp(u - i, 0.0, 1.0);
  const Eigen::Vector3d p1 = c[i], p2 = c[i + 1];
  const Eigen::Vector3d p0 = i > 0 ? c[i - 1] : Eigen::Vector3d(2.0 * p1 - p2);
  const Eigen::Vector3d p3 = i + 2 < n ? c[i + 2] : Eigen::Vector3d(2.0 * p2 - p1);
  // Knot spacing = sqrt(chord length): the centripetal parameterisation.
  auto knot = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::max(std::sqrt((b - a).norm()), 1e-9); };
  const double t0 = 0.0, t1 = t0 + knot(p0, p1), t2 = t1 + knot(p1, p2), t3 = t2 + knot(p2, p3);
  const double s = t1 + t * (t2 - t1);
  // Barry-Goldman pyramid.
  const Eigen::Vector3d a1 = (t1 - s) / (t1 - t0) * p0 + (s - t0) / (t1 - t0) * p1;
  const Eigen::Vector3d a2 = (t2 - s) / (t2 - t1) * p1 + (s - t1) / (t2 - t1) * p2;
  const Eigen::Vector3d a3 = (t3 - s) / (t3 - t2) * p2 + (s - t2) / (t3 - t2) * p3;
  const Eigen::Vector3d b1 = (t2 - s) / (t2 - t0) * a1 + (s - t0) / (t2 - t0) * a2;
  const Eigen::Vector3d b2 = (t3 - s) / (t3 - t1) * a2 + (s - t1) / (t3 - t1) * a3;
  return (t2 - s) / (t2 - t1) * b1 + (s - t1) / (t2 - t1) * b2;
}

std::vector<double> catmull_rom_parameters(const std::vector<Eigen::Vector3d>& c, double spacing) {
  std::vector<double> us{0.0};
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    // Estimate the segment's length from a fine probe, then split it evenly.
    double length = 0.0;
    Eigen::Vector3d prev = c[i];
    for (int k = 1; k <= 16; ++k) {
      const Eigen::Vector3d p = catmull_rom_point(c, i + k / 16.0);
      length += (p - prev).norm();
      prev = p;
    }
    const int steps = std::max(1, static_cast<int>(std::ceil(1.05 * length / spacing)));
    for (int k = 1; k <= steps; ++k) us.push_back(k == steps ? static_cast<double>(i + 1) : i + double(k) / steps);
  }
  return us;
}

}  // namespace gw
