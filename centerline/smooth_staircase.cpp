#include "centerline/smooth_staircase.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace gw {

double lattice_area_share(const TriangleMesh& m) {
  const std::array<Eigen::Vector3d, 3> lattice = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 1, 1) / std::sqrt(2.0),
                                                  Eigen::Vector3d(1, 1, 1) / std::sqrt(3.0)};
  double total = 0.0, on_lattice = 0.0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area = n.norm();
    if (!(area > 0)) continue;
    total += area;
    Eigen::Vector3d s = (n / area).cwiseAbs();
    std::sort(s.data(), s.data() + 3);
    for (const Eigen::Vector3d& l : lattice)
      if ((s - l).norm() < 0.03) {
        on_lattice += area;
        break;
      }
  }
  return total > 0 ? on_lattice / total : 0.0;
}

TriangleMesh taubin_smooth(const TriangleMesh& mesh, int passes, double lambda, double mu) {
  const Eigen::Index n = mesh.V.rows();
  // Unique neighbours of every vertex, in compressed rows.
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<size_t>(mesh.F.rows()) * 6);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      edges.emplace_back(a, b);
      edges.emplace_back(b, a);
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<int> start(static_cast<size_t>(n) + 1, 0);
  for (const auto& e : edges) ++start[static_cast<size_t>(e.first) + 1];
  for (size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];

  TriangleMesh out = mesh;
  Eigen::MatrixX3d next(n, 3);
  auto step = [&](double factor) {
    for (Eigen::Index v = 0; v < n; ++v) {
      const int b = start[static_cast<size_t>(v)], e = start[static_cast<size_t>(v) + 1];
      if (e == b) {
        next.row(v) = out.V.row(v);
        continue;
      }
      Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
      for (int i = b; i < e; ++i) mean += out.V.row(edges[static_cast<size_t>(i)].second);
      mean /= double(e - b);
      next.row(v) = out.V.row(v) + factor * (mean - out.V.row(v));
    }
    out.V.swap(next);
  };
  for (int p = 0; p < passes; ++p) {
    step(lambda);
    step(-mu);
  }
  return out;
}

}  // namespace gw
