#include "anatomy_gen/open_ends.hpp"

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "base/mesh/validate_mesh.hpp"
#include "base/mesh/weld_vertices.hpp"

namespace gw {

TriangleMesh remove_end_caps(const TriangleMesh& mesh, const std::vector<EndCap>& caps, double tolerance) {
  // Which cap (if any) each vertex lies on.
  std::vector<int> on_cap(static_cast<size_t>(mesh.V.rows()), -1);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d p = mesh.V.row(v);
    for (size_t c = 0; c < caps.size(); ++c) {
      const Eigen::Vector3d d = p - caps[c].center;
      const double height = d.dot(caps[c].normal);
      if (std::abs(height) <= tolerance && (d - height * caps[c].normal).norm() <= caps[c].radius * 1.01 + tolerance)
        on_cap[static_cast<size_t>(v)] = static_cast<int>(c);
    }
  }
  std::vector<int> keep;
  std::vector<int> removed(caps.size(), 0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = on_cap[mesh.F(f, 0)], b = on_cap[mesh.F(f, 1)], c = on_cap[mesh.F(f, 2)];
    if (a >= 0 && a == b && b == c) ++removed[static_cast<size_t>(a)];
    else keep.push_back(static_cast<int>(f));
  }
  for (size_t c = 0; c < caps.size(); ++c)
    if (removed[c] == 0) throw MeshError("open ends: no faces found on cap " + std::to_string(c));
  TriangleMesh open;
  open.V = mesh.V;
  open.F.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) open.F.row(static_cast<Eigen::Index>(i)) = mesh.F.row(keep[i]);
  open = weld_vertices(open);  // drops the now unreferenced cap-interior vertices
  // The mesher cuts the cap's sharp rim with small chamfer triangles, so the hole's border
  // runs slightly inside the rim: move the border vertices (already on the cap plane)
  // radially onto the rim circle, which lies exactly on the tube surface.
  std::map<std::pair<int, int>, int> edge_use;
  for (Eigen::Index f = 0; f < open.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = open.F(f, k), b = open.F(f, (k + 1) % 3);
      ++edge_use[{std::min(a, b), std::max(a, b)}];
    }
  std::set<int> border;
  for (const auto& [edge, count] : edge_use)
    if (count == 1) border.insert({edge.first, edge.second});
  for (int v : border) {
    const Eigen::Vector3d p = open.V.row(v);
    const EndCap* nearest = nullptr;
    double best = INFINITY;
    for (const EndCap& cap : caps) {
      const double d = std::abs((p - cap.center).dot(cap.normal)) + std::max(0.0, (p - cap.center).norm() - cap.radius);
      if (d < best) best = d, nearest = &cap;
    }
    const Eigen::Vector3d d = p - nearest->center;
    const Eigen::Vector3d radial = d - d.dot(nearest->normal) * nearest->normal;
    if (radial.norm() > 1e-9) open.V.row(v) = (nearest->center + nearest->radius * radial.normalized()).transpose();
  }
  const MeshReport report = validate_mesh(open);
  if (report.boundary_loops != static_cast<long>(caps.size()) || report.non_manifold_edges != 0 ||
      report.components != 1 || report.degenerate_faces != 0)
    throw MeshError("open ends: removing the caps left " + std::to_string(report.boundary_loops) + " holes for " +
                    std::to_string(caps.size()) + " ends");
  return open;
}

}  // namespace gw
