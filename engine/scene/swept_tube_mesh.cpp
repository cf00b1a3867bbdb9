#include "engine/scene/swept_tube_mesh.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <vector>
#include <stdexcept>

namespace gw {

TriangleMesh swept_tube_mesh(const Eigen::MatrixX3d& c, double radius, int segments) {
  const int n = static_cast<int>(c.rows());
  if (n < 2 || !(radius > 0) || segments < 3 || !c.allFinite())
    throw std::invalid_argument("swept_tube_mesh: need >= 2 finite points, radius > 0 and >= 3 segments");
  // Tangent per point: the mean of its neighbouring segment directions.
  std::vector<Eigen::Vector3d> t(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    if (i > 0) d += (c.row(i) - c.row(i - 1)).transpose().normalized();
    if (i + 1 < n) d += (c.row(i + 1) - c.row(i)).transpose().normalized();
    if (!(d.norm() > 1e-12)) throw std::invalid_argument("swept_tube_mesh: repeated or reversed centreline points");
    t[i] = d.normalized();
  }
  // Parallel transport of the normal u along the tangents.
  std::vector<Eigen::Vector3d> u(n);
  u[0] = t[0].unitOrthogonal();
  for (int i = 1; i < n; ++i) {
    const Eigen::Vector3d p = u[i - 1] - u[i - 1].dot(t[i]) * t[i];
    u[i] = p.norm() > 1e-9 ? p.normalized() : t[i].unitOrthogonal();
  }
  TriangleMesh m;
  m.V.resize(n * segments + 2, 3);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d v = t[i].cross(u[i]);
    for (int j = 0; j < segments; ++j) {
      const double a = 2.0 * M_PI * j / segments;
      m.V.row(i * segments + j) = c.row(i) + radius * (std::cos(a) * u[i] + std::sin(a) * v).transpose();
    }
  }
  const int start = n * segments, end = start + 1;
  m.V.row(start) = c.row(0);
  m.V.row(end) = c.row(n - 1);
  m.F.resize(2 * (n - 1) * segments + 2 * segments, 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j < segments; ++j) {
      const int a = i * segments + j, b = i * segments + (j + 1) % segments;
      const int cc = (i + 1) * segments + (j + 1) % segments, d = (i + 1) * segments + j;
      m.F.row(f++) << a, b, d;  // (b - a) x (d - a) ~ v x t = u: outward
      m.F.row(f++) << b, cc, d;
    }
  for (int j = 0; j < segments; ++j) {
    const int jn = (j + 1) % segments;
    m.F.row(f++) << start, jn, j;                                      // normal -t at the start
    m.F.row(f++) << end, (n - 1) * segments + j, (n - 1) * segments + jn;  // +t at the end
  }
  return m;
}

}  // namespace gw
