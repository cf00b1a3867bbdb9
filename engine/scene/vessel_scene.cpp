#include "engine/scene/vessel_scene.hpp"

#include <algorithm>
#include <cmath>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "engine/scene/closest_point_triangle.hpp"
#include "engine/scene/nearest_face.hpp"

namespace gw {

// Built on first use (scene_bvh): only the moving wall's queries and the exact slow path need it, and it is
// about half of a scene's memory (a training server holds a hundred scenes).
struct VesselSceneBvh {
  std::once_flag built;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> model;
  std::unique_ptr<fcl::CollisionObjectd> object;
};

namespace {

// The scene's FCL BVH, built from its mesh the first time it is asked for (thread-safe).
const fcl::CollisionObjectd* scene_bvh(const VesselScene& scene) {
  VesselSceneBvh& b = *scene.bvh;
  std::call_once(b.built, [&] {
    const TriangleMesh& mesh = scene.mesh;
    std::vector<fcl::Vector3d> verts(mesh.V.rows());
    std::vector<fcl::Triangle> tris(mesh.F.rows());
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) verts[i] = mesh.V.row(i).transpose();
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) tris[f] = fcl::Triangle(mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2));
    b.model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
    b.model->beginModel(static_cast<int>(tris.size()), static_cast<int>(verts.size()));
    b.model->addSubModel(verts, tris);
    b.model->endModel();
    b.object = std::make_unique<fcl::CollisionObjectd>(b.model, fcl::Transform3d::Identity());
  });
  return b.object.get();
}

}  // namespace

VesselScene make_vessel_scene(const TriangleMesh& mesh) {
  const int nv = static_cast<int>(mesh.V.rows());
  const int nf = static_cast<int>(mesh.F.rows());
  if (nv == 0 || nf == 0) throw std::runtime_error("make_vessel_scene: the vessel mesh is empty");
  if (!mesh.V.allFinite()) throw std::runtime_error("make_vessel_scene: the vessel mesh has non-finite vertices");
  if (mesh.F.minCoeff() < 0 || mesh.F.maxCoeff() >= nv)
    throw std::runtime_error("make_vessel_scene: a triangle indexes a vertex that does not exist");
  VesselScene s;
  s.mesh = mesh;
  s.face_normals.resize(nf, 3);
  s.face_centres.resize(nf, 3);
  s.face_radii.resize(nf);
  double volume = 0;
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    s.face_normals.row(f) = len > 0 ? Eigen::RowVector3d((n / len).transpose()) : Eigen::RowVector3d::Zero();
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    s.face_centres.row(f) = centre.transpose();
    s.face_radii(f) = std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()});
    s.face_spheres.emplace_back(centre.x(), centre.y(), centre.z(), s.face_radii(f));
    // The plane bound needs a normal accurate to 1e-10: the cross product's rounding, relative to its
    // length, is a few 1e-16 over the sine of the face's angle at a.
    const bool thin = !(len >= 1e-4 * (b - a).norm() * (c - a).norm());
    const Eigen::Vector3d unit = thin ? Eigen::Vector3d::Zero() : Eigen::Vector3d(n / len);
    s.face_planes.emplace_back(unit.x(), unit.y(), unit.z(), unit.dot(a));
    Eigen::Matrix3d corners;
    corners << a, b, c;
    s.face_corners.push_back(corners);
    volume += a.dot(b.cross(c)) / 6.0;
  }
  // Angle-weighted vertex normals (Thurmer & Wuthrich 1998).
  s.vertex_normals = Eigen::MatrixX3d::Zero(nv, 3);
  for (int f = 0; f < nf; ++f) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p0 = mesh.V.row(mesh.F(f, c)), p1 = mesh.V.row(mesh.F(f, (c + 1) % 3)),
                            p2 = mesh.V.row(mesh.F(f, (c + 2) % 3));
      const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
      const double den = e1.norm() * e2.norm();
      const double angle = den > 0 ? std::acos(std::clamp(e1.dot(e2) / den, -1.0, 1.0)) : 0.0;
      s.vertex_normals.row(mesh.F(f, c)) += angle * s.face_normals.row(f);
    }
  }
  for (int i = 0; i < nv; ++i) {
    const double len = s.vertex_normals.row(i).norm();
    if (len > 0) s.vertex_normals.row(i) /= len;
  }
  if (!(volume > 0))
    throw std::runtime_error("make_vessel_scene: the vessel mesh has signed volume " + std::to_string(volume) +
                             " <= 0 (not closed or oriented inwards); the lumen must be the inside");
  s.bvh = std::make_shared<VesselSceneBvh>();  // built on first use
  s.grid = std::make_shared<const TriangleGrid>(make_triangle_grid(mesh));
  return s;
}

void triangles_near(const VesselScene& scene, const Eigen::Vector3d& p, double radius, std::vector<int>& out) {
  grid_candidates(*scene.grid, p, radius, out);
  // Keep the triangles whose bounding sphere reaches the query sphere.
  std::size_t kept = 0;
  for (const int f : out) {
    const Eigen::Vector4d& sphere = scene.face_spheres[f];
    if ((p - sphere.head<3>()).norm() - sphere[3] <= radius) out[kept++] = f;
  }
  out.resize(kept);
}

void triangles_within(const VesselScene& scene, const Eigen::Vector3d& p, double radius, std::vector<int>& out) {
  out.clear();
  auto sphere = std::make_shared<fcl::Sphered>(radius);
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.translation() = p;
  fcl::CollisionObjectd obj(sphere, tf);
  fcl::CollisionRequestd req(static_cast<std::size_t>(scene.mesh.F.rows()), false);
  fcl::CollisionResultd res;
  fcl::collide(scene_bvh(scene), &obj, req, res);
  for (std::size_t i = 0; i < res.numContacts(); ++i) out.push_back(res.getContact(i).b1);
}

double nearest_triangle(const VesselScene& scene, const Eigen::Vector3d& p, int& triangle) {
  // A tiny sphere stands in for the point (FCL has no point shape).
  auto sphere = std::make_shared<fcl::Sphered>(1e-9);
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.translation() = p;
  fcl::CollisionObjectd obj(sphere, tf);
  fcl::DistanceRequestd req(true);
  fcl::DistanceResultd res;
  fcl::distance(scene_bvh(scene), &obj, req, res);
  triangle = res.b1;
  return std::max(0.0, res.min_distance);
}

WallDistance wall_distance_among(const VesselScene& scene, const Eigen::Vector3d& p, const std::vector<int>& triangles,
                                 double cutoff, const std::vector<double>* lower_bounds, double moved, int* hint,
                                 const std::vector<Eigen::Vector4d>* bounds) {
  NearestFace best(cutoff);
  const auto& V = scene.mesh.V;
  const auto& F = scene.mesh.F;
  auto consider = [&](int position) {
    const int f = triangles[position];
    // Early out: the triangle lies inside its bounding sphere.
    const Eigen::Vector4d& sphere = bounds ? (*bounds)[2 * position] : scene.face_spheres[f];
    const double centre_distance = (p - sphere.head<3>()).norm();
    const double dc = centre_distance - sphere[3];
    if (dc > 0 && dc * dc > best.d2 * (1 + 1e-12)) return;
    // Second early out: the triangle lies in its plane, |n.p - n.a| <= its distance. Taken only where
    // the triangle is then farther than the best by more than the tie tolerance of NearestFace
    // (1e-12 (1 + d2)), however the two distances round: the slack covers the normal's error
    // (face_planes: below 1e-10 of |p - a| <= centre_distance + radius) and the products' rounding, the
    // margins the tie band. So the triangle would not have replaced the best; skipping it leaves the
    // answer as it was.
    const Eigen::Vector4d& plane = bounds ? (*bounds)[2 * position + 1] : scene.face_planes[f];
    const double slack = 1e-9 * (1 + centre_distance + sphere[3]) + 1e-13 * std::abs(plane[3]);
    const double dp = std::abs(plane.head<3>().dot(p) - plane[3]) - slack;
    if (dp > 0 && dp * dp > best.d2 * (1 + 1e-9) + 1e-11) return;
    int region = 0;
    const Eigen::Matrix3d& tri = scene.face_corners[f];
    const Eigen::Vector3d c = closest_point_on_triangle(p, tri.col(0), tri.col(1), tri.col(2), region);
    const Eigen::Vector3d diff = p - c;
    best.offer(f, position, c, diff, diff.squaredNorm(), scene.face_normals.row(f).transpose());
  };
  // The hinted triangle first (usually the last query's closest): a tight best distance from the start
  // lets the bounding-sphere test reject nearly every other triangle.
  const int first = hint ? *hint : -1;
  if (first >= 0 && first < static_cast<int>(triangles.size())) consider(first);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    if (lower_bounds) {
      const double lb = (*lower_bounds)[i] - moved;
      if (lb > 0 && lb * lb > best.d2 * (1 + 1e-9) + 1e-18) break;  // sorted: nothing later is closer
    }
    if (static_cast<int>(i) != first) consider(static_cast<int>(i));
  }
  if (hint) *hint = best.position;
  if (best.triangle < 0) return to_wall_distance(best, p, p, p, [](int) { return Eigen::Vector3d::Zero(); });
  const int f = best.triangle;
  return to_wall_distance(best, V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose(),
                          [&](int k) -> Eigen::Vector3d { return scene.vertex_normals.row(F(f, k)).transpose(); });
}

WallDistance wall_distance(const VesselScene& scene, const Eigen::Vector3d& p) {
  int tri = -1;
  const double d = nearest_triangle(scene, p, tri);
  std::vector<int> cand;
  triangles_within(scene, p, d + 1e-6 + 1e-9 * (1 + d), cand);
  if (tri >= 0) cand.push_back(tri);
  return wall_distance_among(scene, p, cand, d + 1e-3 + 1e-6 * d);
}

}  // namespace gw
