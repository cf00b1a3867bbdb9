#include "centerline/extract/prepare_surface.hpp"

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Random.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Midpoint_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <array>
#include <iterator>
#include <set>
#include <stdexcept>

namespace gw {
namespace {

using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using SMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

Eigen::Vector3d to_eigen(const Point& p) { return {p.x(), p.y(), p.z()}; }

// Direct halfedge construction; false when a face would make the mesh non-manifold or
// repeats an index (the soup path below then repairs it).
bool build_directly(const TriangleMesh& mesh, SMesh& sm) {
  std::vector<SMesh::Vertex_index> vertex;
  vertex.reserve(static_cast<size_t>(mesh.V.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    vertex.push_back(sm.add_vertex(Point(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2))));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    const int n = static_cast<int>(mesh.V.rows());
    if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n || a == b || b == c || a == c) return false;
    if (sm.add_face(vertex[a], vertex[b], vertex[c]) == SMesh::null_face()) return false;
  }
  // Isolated vertices would make later steps fail; a clean surface has none.
  for (auto v : sm.vertices())
    if (sm.is_isolated(v)) return false;
  return true;
}

SMesh to_surface_mesh(const TriangleMesh& mesh) {
  {
    SMesh sm;
    if (build_directly(mesh, sm)) return sm;
  }
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> faces;
  points.reserve(static_cast<size_t>(mesh.V.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) points.emplace_back(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    std::array<std::size_t, 3> face;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(f, k);
      if (v < 0 || v >= mesh.V.rows()) throw std::runtime_error("face " + std::to_string(f) + " has an invalid vertex index");
      face[k] = static_cast<std::size_t>(v);
    }
    faces.push_back(face);
  }
  // Soup repair first: STL exports carry duplicate and degenerate faces; orienting the
  // soup duplicates vertices shared by several sheets so the result is a 2-manifold.
  PMP::repair_polygon_soup(points, faces);
  PMP::orient_polygon_soup(points, faces);
  SMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, faces, sm);
  return sm;
}

TriangleMesh to_triangle_mesh(const SMesh& sm) {
  TriangleMesh out;
  out.V.resize(static_cast<Eigen::Index>(sm.number_of_vertices()), 3);
  out.F.resize(static_cast<Eigen::Index>(sm.number_of_faces()), 3);
  std::vector<int> index(sm.num_vertices(), -1);
  int n = 0;
  for (auto v : sm.vertices()) {
    index[v.idx()] = n;
    out.V.row(n++) = to_eigen(sm.point(v)).transpose();
  }
  int f = 0;
  for (auto face : sm.faces()) {
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(face), sm)) out.F(f, k++) = index[v.idx()];
    ++f;
  }
  return out;
}

}  // namespace

ClosedSurface close_surface(const TriangleMesh& mesh) {
  if (mesh.F.rows() == 0) throw std::runtime_error("the surface has no faces");
  if (!mesh.V.allFinite()) throw std::runtime_error("the surface has non-finite vertex coordinates");
  SMesh sm = to_surface_mesh(mesh);
  ClosedSurface out;
  out.dropped_components = static_cast<int>(PMP::keep_largest_connected_components(sm, 1));
  sm.collect_garbage();
  if (sm.number_of_faces() < 4) throw std::runtime_error("the surface has fewer than 4 usable faces");

  // Cap every boundary loop; the loop's centroid and size become a terminal candidate.
  std::vector<SMesh::Halfedge_index> holes;
  {
    std::set<SMesh::Halfedge_index> seen;
    for (auto h : sm.halfedges()) {
      if (!sm.is_border(h) || seen.count(h)) continue;
      SurfaceCap cap;
      std::vector<Eigen::Vector3d> loop;
      auto g = h;
      do {
        seen.insert(g);
        loop.push_back(to_eigen(sm.point(sm.target(g))));
        g = sm.next(g);
      } while (g != h);
      for (const auto& p : loop) cap.centre += p;
      cap.centre /= double(loop.size());
      Eigen::Vector3d area_vector = Eigen::Vector3d::Zero();
      for (size_t i = 0; i < loop.size(); ++i) {
        cap.radius += (loop[i] - cap.centre).norm();
        area_vector += (loop[i] - cap.centre).cross(loop[(i + 1) % loop.size()] - cap.centre);
      }
      cap.radius /= double(loop.size());
      if (area_vector.norm() > 0) cap.normal = area_vector.normalized();
      holes.push_back(h);
      out.caps.push_back(cap);
    }
  }
  for (auto h : holes) {
    std::vector<SMesh::Face_index> patch;
    PMP::triangulate_hole(sm, h, std::back_inserter(patch));
  }
  if (!CGAL::is_closed(sm) || !CGAL::is_triangle_mesh(sm))
    throw std::runtime_error("the surface cannot be closed into a triangle 2-manifold (holes that cannot be capped)");
  // Border halfedges of an outward-oriented surface run counter-clockwise seen from
  // outside the hole, so the loop's area vector points out of the vessel; flip the
  // cap normals with the surface when it had to be reversed.
  if (PMP::volume(sm) < 0) {
    PMP::reverse_face_orientations(sm);
    for (auto& cap : out.caps) cap.normal = -cap.normal;
  }
  out.volume = PMP::volume(sm);
  out.area = PMP::area(sm);
  if (!(out.volume > 0) || !(out.area > 0)) throw std::runtime_error("the surface encloses no volume");
  out.mesh = to_triangle_mesh(sm);
  return out;
}

TriangleMesh remesh_surface(const TriangleMesh& closed, double edge_length, int iterations) {
  if (!(edge_length > 0)) throw std::runtime_error("remeshing needs a positive edge length");
  CGAL::get_default_random() = CGAL::Random(0);  // deterministic output, whatever ran before
  SMesh sm = to_surface_mesh(closed);
  // A dense input (segmentations and generated anatomies come at a fraction of the
  // radius per edge) is first decimated by shortest-edge collapse, which is far cheaper
  // per removed edge than the remesher's collapse pass; the remesher then evens it out.
  namespace SMS = CGAL::Surface_mesh_simplification;
  SMS::edge_collapse(sm, SMS::Edge_length_stop_predicate<double>(0.5 * edge_length),
                     CGAL::parameters::get_cost(SMS::Edge_length_cost<SMesh>())
                         .get_placement(SMS::Midpoint_placement<SMesh>()));
  sm.collect_garbage();
  // No projection back onto the input: it costs an AABB query per vertex per pass on
  // the (possibly dense) input, and MCF needs the shape, not sub-edge fidelity; every
  // measurement afterwards is taken on the original wall.
  PMP::isotropic_remeshing(faces(sm), edge_length, sm,
                           PMP::parameters::number_of_iterations(iterations).do_project(false));
  sm.collect_garbage();
  return to_triangle_mesh(sm);
}

}  // namespace gw
