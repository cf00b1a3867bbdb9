#include "centerline/alpha_wrap_surface.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "centerline/deterministic_heap.hpp"

namespace gw {

TriangleMesh alpha_wrap_surface(const TriangleMesh& soup, double alpha, double offset) {
  if (!(alpha > 0) || !(offset > 0) || !std::isfinite(alpha) || !std::isfinite(offset))
    throw std::runtime_error("alpha wrapping needs a positive alpha and offset");
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = K::Point_3;
  using SMesh = CGAL::Surface_mesh<Point>;

  TriangleMesh out;
  DeterministicHeapScope heap;  // the wrap's queues may order by handle address
  {
    CGAL::get_default_random() = CGAL::Random(0);
    std::vector<Point> points;
    std::vector<std::array<std::size_t, 3>> faces;
    points.reserve(static_cast<size_t>(soup.V.rows()));
    for (Eigen::Index i = 0; i < soup.V.rows(); ++i) points.emplace_back(soup.V(i, 0), soup.V(i, 1), soup.V(i, 2));
    for (Eigen::Index f = 0; f < soup.F.rows(); ++f) {
      const int a = soup.F(f, 0), b = soup.F(f, 1), c = soup.F(f, 2);
      if (a == b || b == c || a == c) continue;
      faces.push_back({static_cast<std::size_t>(a), static_cast<std::size_t>(b), static_cast<std::size_t>(c)});
    }
    if (faces.empty()) throw std::runtime_error("alpha wrapping: the input has no triangle");
    SMesh wrap;
    CGAL::alpha_wrap_3(points, faces, alpha, offset, wrap);
    if (wrap.number_of_faces() == 0) throw std::runtime_error("alpha wrapping produced an empty surface");
    if (CGAL::Polygon_mesh_processing::volume(wrap) < 0) CGAL::Polygon_mesh_processing::reverse_face_orientations(wrap);

    DeterministicHeapScope::Pause pause;  // the result outlives the region
    out.V.resize(static_cast<Eigen::Index>(wrap.number_of_vertices()), 3);
    out.F.resize(static_cast<Eigen::Index>(wrap.number_of_faces()), 3);
    std::vector<int> index(wrap.num_vertices(), -1);
    int n = 0;
    for (auto v : wrap.vertices()) {
      const Point& p = wrap.point(v);
      index[v.idx()] = n;
      out.V.row(n++) << CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z());
    }
    int f = 0;
    for (auto face : wrap.faces()) {
      int k = 0;
      for (auto v : CGAL::vertices_around_face(wrap.halfedge(face), wrap)) out.F(f, k++) = index[v.idx()];
      ++f;
    }
  }
  return out;
}

}  // namespace gw
