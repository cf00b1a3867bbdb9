#pragma once
// The vessel wall: the triangle mesh, per-face data for exact closest points and an FCL BVH
// over it for the broad phase. Constant while stepping; copies share the BVH.
// With `motion` (engine/scene/wall_motion.hpp) the mesh is the REST configuration of a moving wall and
// the queries of engine/scene/moving_wall.hpp answer at a time t; without, the wall is rigid and static.
// The lumen is the INSIDE of the closed, outward-oriented surface: the wire must stay inside.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "base/mesh/triangle_mesh.hpp"
#include "engine/scene/triangle_grid.hpp"

namespace gw {

struct VesselSceneBvh;  // FCL objects, hidden so FCL headers stay out of every includer
struct WallMotion;

struct VesselScene {
  TriangleMesh mesh;
  Eigen::MatrixX3d face_normals;        // unit outward normals
  Eigen::MatrixX3d vertex_normals;      // angle-weighted unit outward normals (smooth contact normals)
  Eigen::MatrixX3d face_centres;        // bounding-sphere centres (centroids)
  Eigen::VectorXd face_radii;           // bounding-sphere radii around the centroids
  std::vector<Eigen::Vector4d> face_spheres;  // (centre, radius) packed per face for the hot loop
  std::vector<Eigen::Matrix3d> face_corners;  // columns a, b, c per face (contiguous)
  // (n, n.a) per face: unit outward normal and offset, for the lower bound |n.p - n.a| of a point's
  // distance to the face (wall_distance_among); n = 0 (no bound) for a face too thin for its computed
  // normal to be trusted to 1e-10 (sine of its widest angle below 1e-4).
  std::vector<Eigen::Vector4d> face_planes;
  std::shared_ptr<VesselSceneBvh> bvh;         // FCL's, built on first use (copies of the scene share it)
  std::shared_ptr<const TriangleGrid> grid;   // range queries of the per-point candidate lists
  std::shared_ptr<const WallMotion> motion;   // nullptr: a static wall (attach_wall_motion sets it)
};

// Builds the scene (its FCL BVH on first use). Throws std::runtime_error for an empty mesh, non-finite vertices,
// bad indices or a non-positive signed volume (inward-facing normals would turn "inside the vessel" into
// "outside").
VesselScene make_vessel_scene(const TriangleMesh& mesh);

// Closest wall point to `p`, signed clearance (> 0 inside the lumen) and the direction into the lumen.
// `inward` is the Phong-interpolated vertex normal at the closest point (negated): it turns smoothly as
// a point slides over the facets, where facet normals would jump by the facet angle and make a wire
// pressed on the wall chatter sideways.
struct WallDistance {
  double signed_distance = 0;                          // distance to the surface, positive inside
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();
  Eigen::Vector3d inward = Eigen::Vector3d::Zero();    // unit, from the wall towards the lumen
  int triangle = -1;
};

// Exact closest point among all triangles (FCL distance query + exact refinement). Slow path:
// for tests and one-off queries; stepping uses cached candidate lists (engine/contact).
WallDistance wall_distance(const VesselScene& scene, const Eigen::Vector3d& p);

// Closest point among `triangles` only; signed_distance = +inf and triangle = -1 if none is within
// `cutoff`. Triangles whose bounding sphere or plane (face_planes) is farther than the best so far are
// skipped (the plane only where it proves the triangle farther by more than the tie tolerance and any
// rounding: the answer is the one of scanning them). `bounds`: optional, 2 per triangle in list order,
// its face_spheres and face_planes entries (read in order instead of scattered over the scene). With
// `lower_bounds` (ascending, one per triangle, lower bounds of the distance to a point `moved` away
// from p), the scan stops at the first triangle that cannot be closer than the best. `hint`: in, a
// position in `triangles` to try before the others (e.g. the previous closest; the result does not
// depend on it); out, the position of the closest triangle (-1 if none).
WallDistance wall_distance_among(const VesselScene& scene, const Eigen::Vector3d& p, const std::vector<int>& triangles,
                                 double cutoff, const std::vector<double>* lower_bounds = nullptr, double moved = 0,
                                 int* hint = nullptr, const std::vector<Eigen::Vector4d>* bounds = nullptr);

// Every triangle within `radius` of `p` (FCL sphere-vs-BVH collision query), appended to `out` after
// clearing it.
void triangles_within(const VesselScene& scene, const Eigen::Vector3d& p, double radius, std::vector<int>& out);

// Every triangle whose bounding sphere is within `radius` of `p` (grid range query): a superset of
// triangles_within's answer, found ~100x faster; appended to `out` after clearing it.
void triangles_near(const VesselScene& scene, const Eigen::Vector3d& p, double radius, std::vector<int>& out);

// Unsigned distance from `p` to the nearest triangle and that triangle (FCL distance query).
double nearest_triangle(const VesselScene& scene, const Eigen::Vector3d& p, int& triangle);

}  // namespace gw
