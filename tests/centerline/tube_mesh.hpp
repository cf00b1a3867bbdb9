#pragma once
// Test surfaces with a known centerline: a tube swept along a polyline (parallel-transport
// frames), flat-capped or open, optionally with noisy vertices.
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "base/graph/centerline_graph.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw::test {

// Points along an arc of radius `bend` (in the x-y plane, starting at the origin along +x)
// turning by `angle` radians; a straight segment of length `length` when bend <= 0.
inline std::vector<Eigen::Vector3d> arc_axis(double length, double bend, double angle, int samples) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i <= samples; ++i) {
    const double t = double(i) / samples;
    if (bend <= 0) p.emplace_back(t * length, 0.0, 0.0);
    else p.emplace_back(bend * std::sin(t * angle), bend * (1 - std::cos(t * angle)), 0.0);
  }
  return p;
}

// A tube of `radius` around `axis` with `sides` vertices per ring; flat caps when
// `capped`; vertices moved by uniform noise of amplitude `noise` (mm) when > 0.
inline TriangleMesh make_tube(const std::vector<Eigen::Vector3d>& axis, double radius, int sides, bool capped,
                              double noise = 0.0, unsigned seed = 7) {
  const int rings = static_cast<int>(axis.size());
  std::vector<Eigen::Vector3d> verts;
  std::vector<Eigen::Vector3i> faces;
  Eigen::Vector3d t0 = (axis[1] - axis[0]).normalized();
  Eigen::Vector3d u = t0.unitOrthogonal();
  for (int i = 0; i < rings; ++i) {
    const Eigen::Vector3d t = (axis[std::min(i + 1, rings - 1)] - axis[std::max(i - 1, 0)]).normalized();
    u = (u - u.dot(t) * t).normalized();  // parallel transport: no twist
    const Eigen::Vector3d v = t.cross(u);
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * M_PI * k / sides;
      verts.push_back(axis[i] + radius * (std::cos(a) * u + std::sin(a) * v));
    }
  }
  for (int i = 0; i + 1 < rings; ++i)
    for (int k = 0; k < sides; ++k) {
      const int a = i * sides + k, b = i * sides + (k + 1) % sides, c = a + sides, d = b + sides;
      faces.emplace_back(a, b, d);
      faces.emplace_back(a, d, c);
    }
  if (capped) {
    const int first = static_cast<int>(verts.size());
    verts.push_back(axis.front());
    verts.push_back(axis.back());
    const int last = (rings - 1) * sides;
    for (int k = 0; k < sides; ++k) {
      faces.emplace_back(first, (k + 1) % sides, k);
      faces.emplace_back(first + 1, last + k, last + (k + 1) % sides);
    }
  }
  if (noise > 0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-noise, noise);
    for (auto& p : verts) p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
  }
  TriangleMesh m;
  m.V.resize(static_cast<Eigen::Index>(verts.size()), 3);
  m.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < verts.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = verts[i].transpose();
  for (size_t i = 0; i < faces.size(); ++i) m.F.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
  return m;
}

// The true centerline of such a tube: one branch, inlet at the axis start.
inline CenterlineGraph tube_truth(const std::vector<Eigen::Vector3d>& axis, double radius) {
  CenterlineGraph g;
  CenterlineBranch b;
  b.points = axis;
  b.radii.assign(axis.size(), radius);
  g.branches.push_back(b);
  g.inlet = {0, axis.front(), 0, radius};
  number_targets(g);
  return g;
}

}  // namespace gw::test
