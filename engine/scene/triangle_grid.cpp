#include "engine/scene/triangle_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace gw {

namespace {

std::int64_t cell_key(const TriangleGrid& g, int x, int y, int z) {
  return (static_cast<std::int64_t>(x) * g.dims.y() + y) * g.dims.z() + z;
}

// Cell index range [lo, hi] covering [a, b] along one axis, clamped to the grid (in floating point
// first: a far query point must not overflow the int cast; lo > hi when [a, b] misses the grid).
void cell_range(const TriangleGrid& g, int axis, double a, double b, int& lo, int& hi) {
  const double top = g.dims[axis];
  lo = static_cast<int>(std::clamp(std::floor((a - g.origin[axis]) / g.cell), 0.0, top));
  hi = static_cast<int>(std::clamp(std::floor((b - g.origin[axis]) / g.cell), -1.0, top - 1));
}

}  // namespace

TriangleGrid make_triangle_grid(const TriangleMesh& mesh, double cell) {
  const int nf = static_cast<int>(mesh.F.rows());
  if (nf == 0 || mesh.V.rows() == 0) throw std::invalid_argument("make_triangle_grid: the mesh is empty");
  TriangleGrid g;
  if (!(cell > 0)) {
    double edges = 0;
    for (int f = 0; f < nf; ++f)
      for (int c = 0; c < 3; ++c) edges += (mesh.V.row(mesh.F(f, c)) - mesh.V.row(mesh.F(f, (c + 1) % 3))).norm();
    cell = std::max(0.25, 2.0 * edges / (3.0 * nf));
  }
  const Eigen::Vector3d lo = mesh.V.colwise().minCoeff().transpose(), hi = mesh.V.colwise().maxCoeff().transpose();
  // Cell keys are 64-bit and per-axis indices int: coarsen the grid of a mesh with a far stray vertex
  // (or of tiny triangles over a huge extent) rather than overflow them.
  while (((hi - lo) / cell).maxCoeff() > 1e6) cell *= 2;
  g.cell = cell;
  g.origin = lo;
  for (int a = 0; a < 3; ++a) g.dims[a] = std::max(1, static_cast<int>(std::floor((hi[a] - lo[a]) / cell)) + 1);
  // (cell key, triangle) pairs, sorted, then compressed into rows.
  std::vector<std::pair<std::int64_t, int>> pairs;
  pairs.reserve(static_cast<std::size_t>(nf) * 4);
  for (int f = 0; f < nf; ++f) {
    Eigen::Vector3d bmin = mesh.V.row(mesh.F(f, 0)).transpose(), bmax = bmin;
    for (int c = 1; c < 3; ++c) {
      bmin = bmin.cwiseMin(mesh.V.row(mesh.F(f, c)).transpose());
      bmax = bmax.cwiseMax(mesh.V.row(mesh.F(f, c)).transpose());
    }
    int r[3][2];
    for (int a = 0; a < 3; ++a) cell_range(g, a, bmin[a], bmax[a], r[a][0], r[a][1]);
    g.first_cell.emplace_back(r[0][0], r[1][0], r[2][0]);
    for (int x = r[0][0]; x <= r[0][1]; ++x)
      for (int y = r[1][0]; y <= r[1][1]; ++y)
        for (int z = r[2][0]; z <= r[2][1]; ++z) pairs.emplace_back(cell_key(g, x, y, z), f);
  }
  std::sort(pairs.begin(), pairs.end());
  g.items.reserve(pairs.size());
  g.item_first_cell.reserve(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (i == 0 || pairs[i].first != pairs[i - 1].first) {
      g.keys.push_back(pairs[i].first);
      g.begin.push_back(static_cast<int>(g.items.size()));
    }
    g.items.push_back(pairs[i].second);
    g.item_first_cell.push_back(g.first_cell[pairs[i].second]);
  }
  g.begin.push_back(static_cast<int>(g.items.size()));
  const std::int64_t columns = static_cast<std::int64_t>(g.dims.x()) * g.dims.y();
  if (columns <= (std::int64_t{1} << 22)) {
    g.column_begin.resize(columns + 1);
    std::size_t k = 0;
    for (std::int64_t c = 0; c <= columns; ++c) {
      while (k < g.keys.size() && g.keys[k] < c * g.dims.z()) ++k;
      g.column_begin[c] = static_cast<int>(k);
    }
  }
  return g;
}

void grid_candidates(const TriangleGrid& g, const Eigen::Vector3d& p, double radius, std::vector<int>& out) {
  out.clear();
  int r[3][2];
  for (int a = 0; a < 3; ++a) {
    cell_range(g, a, p[a] - radius, p[a] + radius, r[a][0], r[a][1]);
    if (r[a][0] > r[a][1]) return;  // the box misses the grid
  }
  for (int x = r[0][0]; x <= r[0][1]; ++x)
    for (int y = r[1][0]; y <= r[1][1]; ++y) {
      // Cells along z are consecutive keys: one binary search per (x, y) column, within the column's
      // keys where the grid indexes them.
      const std::int64_t first = cell_key(g, x, y, r[2][0]), last = cell_key(g, x, y, r[2][1]);
      auto lo = g.keys.begin(), hi = g.keys.end();
      if (!g.column_begin.empty()) {
        const std::int64_t column = static_cast<std::int64_t>(x) * g.dims.y() + y;
        hi = g.keys.begin() + g.column_begin[column + 1];
        lo = g.keys.begin() + g.column_begin[column];
      }
      auto it = std::lower_bound(lo, hi, first);
      for (; it != g.keys.end() && *it <= last; ++it) {
        const std::size_t k = static_cast<std::size_t>(it - g.keys.begin());
        const int z = static_cast<int>(*it - cell_key(g, x, y, 0));
        for (int i = g.begin[k]; i < g.begin[k + 1]; ++i) {
          // A triangle spanning several cells is reported by the first of them inside the query box.
          const Eigen::Vector3i& c = g.item_first_cell[i];
          if (std::max(c.x(), r[0][0]) == x && std::max(c.y(), r[1][0]) == y && std::max(c.z(), r[2][0]) == z)
            out.push_back(g.items[i]);
        }
      }
    }
}

}  // namespace gw
