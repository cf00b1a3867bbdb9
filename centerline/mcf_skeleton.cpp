#include "centerline/mcf_skeleton.hpp"

#include "centerline/deterministic_heap.hpp"

#include <CGAL/Random.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/extract_mean_curvature_flow_skeleton.h>

#include <stdexcept>

namespace gw {

RawSkeleton mcf_skeleton(const TriangleMesh& closed) {
  using K = CGAL::Simple_cartesian<double>;
  using Point = K::Point_3;
  using SMesh = CGAL::Surface_mesh<Point>;
  using Skeletonization = CGAL::Mean_curvature_flow_skeletonization<SMesh>;

  SMesh sm;
  std::vector<SMesh::Vertex_index> vertex(static_cast<size_t>(closed.V.rows()));
  for (Eigen::Index i = 0; i < closed.V.rows(); ++i)
    vertex[static_cast<size_t>(i)] = sm.add_vertex(Point(closed.V(i, 0), closed.V(i, 1), closed.V(i, 2)));
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f)
    if (sm.add_face(vertex[closed.F(f, 0)], vertex[closed.F(f, 1)], vertex[closed.F(f, 2)]) == SMesh::null_face())
      throw std::runtime_error("skeletonisation input is not a 2-manifold (face " + std::to_string(f) + ")");
  if (!CGAL::is_closed(sm)) throw std::runtime_error("skeletonisation input is not closed");

  // Heap addresses order the flow's edge collapses (deterministic_heap.hpp): allocate in a
  // private region so one mesh always gives one skeleton, whatever ran before in the process.
  DeterministicHeapScope heap;
  RawSkeleton out;
  {
    // The flow's Voronoi poles come from a Delaunay triangulation whose insertion order is
    // shuffled with CGAL's global random generator; on symmetric (co-spherical) inputs the
    // result depends on that order. Reseed for the same reason.
    CGAL::get_default_random() = CGAL::Random(0);
    Skeletonization::Skeleton skeleton;
    Skeletonization mcf(sm);
    mcf.contract_until_convergence();
    mcf.convert_to_skeleton(skeleton);

    DeterministicHeapScope::Pause pause;  // the result outlives the region
    const auto count = boost::num_vertices(skeleton);
    if (count < 2) throw std::runtime_error("skeletonisation produced no curve");
    out.nodes.resize(count);
    for (auto v : CGAL::make_range(vertices(skeleton))) {
      SkeletonNode& node = out.nodes[v];
      const Point& p = skeleton[v].point;
      node.point = {p.x(), p.y(), p.z()};
      node.surface_vertices = static_cast<int>(skeleton[v].vertices.size());
      for (auto mv : skeleton[v].vertices) {
        const Point& q = sm.point(mv);
        node.centroid += Eigen::Vector3d(q.x(), q.y(), q.z());
      }
      node.centroid = node.surface_vertices > 0 ? Eigen::Vector3d(node.centroid / node.surface_vertices) : node.point;
    }
    for (auto e : CGAL::make_range(edges(skeleton)))
      out.edges.emplace_back(static_cast<int>(source(e, skeleton)), static_cast<int>(target(e, skeleton)));
  }
  return out;
}

}  // namespace gw
