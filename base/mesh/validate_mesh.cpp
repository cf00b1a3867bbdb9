#include "base/mesh/validate_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace gw {
namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

// Counts closed chains of boundary edges. Boundary vertices where two holes touch
// have more than two boundary edges; walking edge by edge still visits each once.
long count_boundary_loops(const std::vector<std::pair<int, int>>& boundary, size_t vertex_count) {
  UnionFind loops(vertex_count);
  std::vector<char> on_boundary(vertex_count, 0);
  for (auto [a, b] : boundary) {
    loops.unite(a, b);
    on_boundary[a] = on_boundary[b] = 1;
  }
  long count = 0;
  for (size_t v = 0; v < vertex_count; ++v)
    if (on_boundary[v] && loops.find(static_cast<int>(v)) == static_cast<int>(v)) ++count;
  return count;
}

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

// Bounds over finite vertices only, so one NaN does not hide the real size: r's bbox, max_extent and
// non_finite_vertices; false when no vertex is finite.
bool measure_bounds(const TriangleMesh& mesh, MeshReport& r) {
  bool any_finite = false;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d p = mesh.V.row(v).transpose();
    if (!p.allFinite()) {
      ++r.non_finite_vertices;
      continue;
    }
    if (!any_finite) r.bbox_min = r.bbox_max = p;
    r.bbox_min = r.bbox_min.cwiseMin(p);
    r.bbox_max = r.bbox_max.cwiseMax(p);
    any_finite = true;
  }
  r.max_extent = (r.bbox_max - r.bbox_min).maxCoeff();
  return any_finite;
}

// Every face: bad references (errors), degenerate faces, the signed volume into `r`; each edge's
// face count into `edge_use` and the faces' vertices joined in `pieces`.
void scan_faces(const TriangleMesh& mesh, MeshReport& r, std::unordered_map<std::uint64_t, int>& edge_use,
                UnionFind& pieces) {
  const double area_eps = 1e-14 * std::max(r.max_extent * r.max_extent, 1e-300);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= r.vertices) {
      r.errors.push_back("face " + std::to_string(f) + " references a vertex that does not exist");
      continue;
    }
    pieces.unite(a, b);
    pieces.unite(b, c);
    ++edge_use[edge_key(a, b)];
    ++edge_use[edge_key(b, c)];
    ++edge_use[edge_key(c, a)];
    const Eigen::Vector3d pa = mesh.V.row(a), pb = mesh.V.row(b), pc = mesh.V.row(c);
    const double area2 = (pb - pa).cross(pc - pa).norm();
    if (a == b || b == c || c == a || !(area2 > area_eps)) ++r.degenerate_faces;
    // Divergence theorem: sum of signed tetrahedra to the origin.
    r.volume += pa.dot(pb.cross(pc)) / 6.0;
  }
}

// r's boundary edges and loops and its non-manifold edges, from each edge's face count.
void count_edges(const std::unordered_map<std::uint64_t, int>& edge_use, size_t nv, MeshReport& r) {
  std::vector<std::pair<int, int>> boundary;
  for (const auto& [key, uses] : edge_use) {
    if (uses == 1) boundary.emplace_back(int(key >> 32), int(key & 0xffffffffu));
    if (uses > 2) ++r.non_manifold_edges;
  }
  r.boundary_edges = static_cast<long>(boundary.size());
  r.boundary_loops = count_boundary_loops(boundary, nv);
}

// r.components: the pieces (of `pieces`) that hold a vertex some face uses.
void count_components(const TriangleMesh& mesh, size_t nv, UnionFind& pieces, MeshReport& r) {
  std::vector<char> used(nv, 0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (mesh.F(f, c) >= 0 && mesh.F(f, c) < r.vertices) used[mesh.F(f, c)] = 1;
  for (size_t v = 0; v < nv; ++v)
    if (used[v] && pieces.find(static_cast<int>(v)) == static_cast<int>(v)) ++r.components;
}

// r's errors and warnings from its counts (the unit warnings only when some vertex is finite).
void add_messages(bool any_finite, MeshReport& r) {
  if (r.faces == 0) r.errors.push_back("no faces");
  if (r.non_finite_vertices > 0)
    r.errors.push_back(std::to_string(r.non_finite_vertices) + " vertices have NaN or infinite coordinates");
  if (r.boundary_loops > 0)
    r.warnings.push_back("surface is open: " + std::to_string(r.boundary_loops) + " boundary loops (" +
                         std::to_string(r.boundary_edges) + " edges); inlets/outlets will be capped");
  if (r.non_manifold_edges > 0)
    r.warnings.push_back(std::to_string(r.non_manifold_edges) + " non-manifold edges (shared by more than two faces)");
  if (r.components > 1)
    r.warnings.push_back(std::to_string(r.components) + " connected components; pieces under 2% of the largest one's area are dropped as islands, larger ones wrapped into one surface");
  if (r.degenerate_faces > 0)
    r.warnings.push_back(std::to_string(r.degenerate_faces) + " degenerate faces (zero area or repeated vertex)");
  if (any_finite && r.max_extent < 1.0)
    r.warnings.push_back("mesh is only " + fmt(r.max_extent) +
                         " units across: probably in metres; use --scale 1000 for millimetres");
  else if (any_finite && r.max_extent < 5.0)
    r.warnings.push_back("mesh is only " + fmt(r.max_extent) +
                         " units across: probably in centimetres; use --scale 10 for millimetres");
  else if (r.max_extent > 5000.0)
    r.warnings.push_back("mesh is " + fmt(r.max_extent) +
                         " units across: probably in micrometres; use --scale 0.001 for millimetres");
}

}  // namespace

MeshReport validate_mesh(const TriangleMesh& mesh) {
  MeshReport r;
  r.vertices = mesh.V.rows();
  r.faces = mesh.F.rows();
  const size_t nv = static_cast<size_t>(mesh.V.rows());
  const bool any_finite = measure_bounds(mesh, r);
  std::unordered_map<std::uint64_t, int> edge_use;
  edge_use.reserve(static_cast<size_t>(3 * r.faces));
  UnionFind pieces(nv);
  scan_faces(mesh, r, edge_use, pieces);
  count_edges(edge_use, nv, r);
  count_components(mesh, nv, pieces, r);
  add_messages(any_finite, r);
  return r;
}

std::string format_report(const MeshReport& r) {
  std::ostringstream s;
  s << "vertices            " << r.vertices << "\n"
    << "faces               " << r.faces << "\n"
    << "bounding box        [" << fmt(r.bbox_min.x()) << ", " << fmt(r.bbox_min.y()) << ", " << fmt(r.bbox_min.z())
    << "] .. [" << fmt(r.bbox_max.x()) << ", " << fmt(r.bbox_max.y()) << ", " << fmt(r.bbox_max.z()) << "]\n"
    << "largest side        " << fmt(r.max_extent) << "\n"
    << "components          " << r.components << "\n"
    << "boundary loops      " << r.boundary_loops << " (" << r.boundary_edges << " edges)\n"
    << "non-manifold edges  " << r.non_manifold_edges << "\n"
    << "degenerate faces    " << r.degenerate_faces << "\n"
    << "non-finite vertices " << r.non_finite_vertices << "\n";
  if (r.closed()) s << "enclosed volume     " << fmt(std::abs(r.volume)) << "\n";
  for (const auto& w : r.warnings) s << "warning: " << w << "\n";
  for (const auto& e : r.errors) s << "error: " << e << "\n";
  return s.str();
}

std::string report_to_json(const MeshReport& r) {
  nlohmann::json j = {
      {"vertices", r.vertices},
      {"faces", r.faces},
      {"bbox_min", {r.bbox_min.x(), r.bbox_min.y(), r.bbox_min.z()}},
      {"bbox_max", {r.bbox_max.x(), r.bbox_max.y(), r.bbox_max.z()}},
      {"max_extent", r.max_extent},
      {"components", r.components},
      {"boundary_loops", r.boundary_loops},
      {"boundary_edges", r.boundary_edges},
      {"non_manifold_edges", r.non_manifold_edges},
      {"degenerate_faces", r.degenerate_faces},
      {"non_finite_vertices", r.non_finite_vertices},
      {"closed", r.closed()},
      {"manifold", r.manifold()},
      {"volume", r.closed() ? std::abs(r.volume) : 0.0},
      {"warnings", r.warnings},
      {"errors", r.errors},
  };
  return j.dump();
}

}  // namespace gw
