#include "anatomy_gen/mesh_tree_surface.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/facets_in_complex_3_to_triangle_mesh.h>
#include <CGAL/make_mesh_3.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>

namespace gw {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using BaseDomain = CGAL::Labeled_mesh_domain_3<K>;

// The labeled implicit domain, with initial points placed on every branch instead of
// found by random rays from a bounding sphere (rays miss thin, far branches).
class SeededDomain : public BaseDomain {
 public:
  using BaseDomain::BaseDomain;
  std::vector<std::pair<Point_3, Index>> seeds;

  struct Construct_initial_points {
    const SeededDomain* domain;
    template <class OutputIterator>
    OutputIterator operator()(OutputIterator out, const int = 0) const {
      for (const auto& s : domain->seeds) *out++ = s;
      return out;
    }
  };
  Construct_initial_points construct_initial_points_object() const { return {this}; }
};

using Tr = CGAL::Mesh_triangulation_3<SeededDomain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

Eigen::Vector3d to_eigen(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }
K::Point_3 to_cgal(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// Facet size = edge_per_radius x radius of the nearest tube.
struct SizeField {
  using FT = K::FT;
  using Index = SeededDomain::Index;
  const TubeField* field;
  double edge_per_radius;
  double min_size;
  FT operator()(const K::Point_3& p, const int, const Index&) const {
    return std::max(min_size, edge_per_radius * field->local_radius(to_eigen(p)));
  }
};

// Surface points along every branch: from the centreline outwards in four directions,
// intersected with the surface (directions that end inside another tube are skipped).
void add_seeds(SeededDomain& domain, const TreeGeometry& g) {
  auto do_intersect = domain.do_intersect_surface_object();
  auto intersect = domain.construct_intersection_object();
  std::vector<Eigen::Vector3d> placed;
  for (const BranchCurve& c : g.branches) {
    // A child's first radius lies inside its parent: nothing to seed there.
    double next = c.parent >= 0 ? c.radii.front() : 0.0;
    for (size_t i = 0; i + 1 < c.points.size(); ++i) {
      if (c.arclength[i] < next) continue;
      next = c.arclength[i] + c.radii[i];
      const Eigen::Vector3d t = (c.points[i + 1] - c.points[i]).normalized();
      const Eigen::Vector3d u = t.unitOrthogonal(), v = t.cross(u);
      for (int k = 0; k < 4; ++k) {
        const double a = k * M_PI / 2.0;
        const Eigen::Vector3d d = std::cos(a) * u + std::sin(a) * v;
        const K::Segment_3 seg(to_cgal(c.points[i]), to_cgal(c.points[i] + (2.0 * c.radii[i] + 0.5) * d));
        const auto patch = do_intersect(seg);
        if (!patch) continue;
        const auto hit = intersect(seg);
        // Two seeds closer than a fraction of the facet size would force needle triangles.
        const Eigen::Vector3d q = to_eigen(std::get<0>(hit));
        const double spacing = 0.5 * g.edge_per_radius * c.radii[i];
        bool crowded = false;
        for (const Eigen::Vector3d& o : placed) crowded = crowded || (o - q).squaredNorm() < spacing * spacing;
        if (crowded) continue;
        placed.push_back(q);
        domain.seeds.emplace_back(std::get<0>(hit), domain.index_from_surface_patch_index(*patch));
      }
    }
  }
}

}  // namespace

TriangleMesh mesh_tree_surface(const TreeGeometry& g, const TubeField& field) {
  namespace params = CGAL::parameters;
  const Eigen::Vector3d center = 0.5 * (g.bbox_min + g.bbox_max);
  const double radius = 0.5 * (g.bbox_max - g.bbox_min).norm() + 2.0 * g.max_radius + 1.0;
  const std::function<double(const K::Point_3&)> f = [&field](const K::Point_3& p) { return field.value(to_eigen(p)); };
  // Bisection stops at 1e-7 x bounding radius: vertices sit on the surface to ~1e-5 mm.
  SeededDomain domain(CGAL::make_implicit_to_labeling_function_wrapper<K>(f),
                      K::Sphere_3(to_cgal(center), radius * radius), 1e-7);
  add_seeds(domain, g);

  // facet_size bounds the surface Delaunay ball radius, not the edge: 0.75 makes the mean
  // edge come out at edge_per_radius x r (measured on the training tubes).
  const SizeField size{&field, 0.75 * g.edge_per_radius, 0.4 * g.edge_per_radius * g.min_radius};
  // Chord error small against the smallest radius; angle bound keeps triangles well shaped.
  const Criteria criteria(params::facet_angle = 25.0, params::facet_size = size,
                          params::facet_distance = 0.03 * g.min_radius,
                          params::facet_topology = CGAL::FACET_VERTICES_ON_SURFACE);
  const C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude(),
                                           params::manifold());

  std::vector<K::Point_3> points;
  std::vector<std::array<std::size_t, 3>> faces;
  CGAL::Mesh_3::internal::facets_in_complex_3_to_triangle_soup(c3t3, C3t3::Subdomain_index(1), points, faces, true,
                                                               false);
  TriangleMesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) mesh.V.row(static_cast<Eigen::Index>(i)) = to_eigen(points[i]).transpose();
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 3; ++k) mesh.F(static_cast<Eigen::Index>(i), k) = static_cast<int>(faces[i][k]);
  return mesh;
}

}  // namespace gw
