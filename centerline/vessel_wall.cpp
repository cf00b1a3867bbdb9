#include "centerline/vessel_wall.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>

#include <vector>

namespace gw {
namespace {
using K = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
Eigen::Vector3d vec(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }

// Moller-Trumbore: distance along the ray to the triangle, or +inf. Both sides count:
// a query point may sit a hair outside a coarse wall.
double ray_triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const K::Triangle_3& t) {
  const Eigen::Vector3d a = vec(t[0]), e1 = vec(t[1]) - a, e2 = vec(t[2]) - a;
  const Eigen::Vector3d pv = d.cross(e2);
  const double det = e1.dot(pv);
  if (std::abs(det) < 1e-300) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d tv = o - a;
  const double u = tv.dot(pv) / det;
  if (u < 0 || u > 1) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d qv = tv.cross(e1);
  const double v = d.dot(qv) / det;
  if (v < 0 || u + v > 1) return std::numeric_limits<double>::infinity();
  const double s = e2.dot(qv) / det;
  return s >= 0 ? s : std::numeric_limits<double>::infinity();
}
}  // namespace

struct VesselWall::Impl {
  Triangles triangles;
  Tree tree;
};

VesselWall::VesselWall(const TriangleMesh& surface) : impl_(std::make_unique<Impl>()) {
  impl_->triangles.reserve(static_cast<size_t>(surface.F.rows()));
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0)), b = surface.V.row(surface.F(f, 1)),
                          c = surface.V.row(surface.F(f, 2));
    if ((b - a).cross(c - a).squaredNorm() <= 0) continue;  // degenerate faces break the tree's queries
    impl_->triangles.emplace_back(point(a), point(b), point(c));
  }
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

VesselWall::~VesselWall() = default;
VesselWall::VesselWall(VesselWall&&) noexcept = default;
VesselWall& VesselWall::operator=(VesselWall&&) noexcept = default;

double VesselWall::distance(const Eigen::Vector3d& p) const {
  return std::sqrt(impl_->tree.squared_distance(point(p)));
}

double VesselWall::ray_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& d, double max_length) const {
  std::vector<Primitive::Id> hits;
  if (std::isfinite(max_length)) {
    const K::Segment_3 segment(point(origin), point(origin + d * max_length));
    impl_->tree.all_intersected_primitives(segment, std::back_inserter(hits));
  } else {
    const K::Ray_3 ray(point(origin), K::Vector_3(d.x(), d.y(), d.z()));
    impl_->tree.all_intersected_primitives(ray, std::back_inserter(hits));
  }
  double best = std::numeric_limits<double>::infinity();
  for (auto it : hits) best = std::min(best, ray_triangle(origin, d, *it));
  return best <= max_length ? best : std::numeric_limits<double>::infinity();
}

}  // namespace gw
