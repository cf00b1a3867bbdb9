#pragma once
// Queries against a moving wall (a VesselScene with `motion`) at a time t, exact on the current
// triangles without rebuilding anything per step: the broad phase (grid) stays on the rest mesh, queried
// through rest_query_ball (a superset), and the candidates' current corners, face normals, bounding
// spheres and angle-weighted vertex normals are computed on demand from the field (each vertex once per
// time per thread). The answers are those of make_vessel_scene(current mesh) (vessel_scene_at).
#include <Eigen/Core>
#include <vector>

#include "engine/scene/vessel_scene.hpp"
#include "engine/scene/wall_motion.hpp"

namespace gw {

// `scene` with `motion` attached (scene.mesh is its rest configuration). A motion that cannot move the
// wall (0 bpm) is baked instead: the result is the static scene of the frozen shape, vessel_scene_at(.., 0),
// so a 0 bpm run is today's static run (the same scene, bit for bit, when the frozen shape is the rest).
VesselScene attach_wall_motion(const VesselScene& scene, const WallMotion& motion);

// The static scene of the wall's shape at time t (a full rebuild: BVH, grid, face data); `scene`
// itself when it has no motion. For output, tests and references.
VesselScene vessel_scene_at(const VesselScene& scene, double t);

// Current position of a vertex at time t (scene.motion required).
Eigen::Vector3d current_wall_vertex(const VesselScene& scene, int vertex, double t);

// wall_distance_among (engine/scene/vessel_scene.hpp) on the triangles' current shape at time t.
// With `rest` (p pulled back, wall_rest_point_at): `lower_bounds` and `moved` are REST-configuration
// distances (each triangle's rest bounding-sphere distance from a rest centre, and |rest->X - centre|);
// a triangle is skipped, without evaluating its current shape, when its rest bounding sphere is farther
// from rest->X than rest_reach(best so far), and the scan stops at the first lower bound beyond it: a
// triangle nearer than the best has its rest point within that reach (wall_motion.hpp). Same answer as
// the plain scan of the same triangles. `rest_spheres`: the triangles' rest bounding spheres in list
// order (else read from the scene).
WallDistance wall_distance_among_at(const VesselScene& scene, double t, const Eigen::Vector3d& p,
                                    const std::vector<int>& triangles, double cutoff,
                                    const std::vector<double>* lower_bounds = nullptr, double moved = 0,
                                    int* hint = nullptr, const RestPoint* rest = nullptr,
                                    const std::vector<Eigen::Vector4d>* rest_spheres = nullptr);

// wall_rest_point (wall_motion.hpp) at time t, with the per-time part of the field cached.
bool wall_rest_point_at(const VesselScene& scene, double t, const Eigen::Vector3d& p, const Eigen::Vector3d* guess,
                        RestPoint& out);

// triangles_near at time t: a superset of the triangles whose current shape comes within `radius` of p
// (from the rest grid through rest_query_ball), each kept only if its current bounding sphere is within
// `radius`. `sphere_distances`, when given, receives each one's current bounding-sphere distance from p.
void triangles_near_at(const VesselScene& scene, double t, const Eigen::Vector3d& p, double radius,
                       std::vector<int>& out, std::vector<double>* sphere_distances = nullptr);

// wall_distance (exact, all triangles) at time t.
WallDistance wall_distance_at(const VesselScene& scene, double t, const Eigen::Vector3d& p);

// Mean velocity over [t, t + h] of the wall point that is at `closest` (on `triangle`) at time t: its
// barycentric coordinates at t applied to the vertices' travel over the interval, divided by h [mm/s].
Eigen::Vector3d wall_point_velocity(const VesselScene& scene, int triangle, const Eigen::Vector3d& closest, double t,
                                    double h);

}  // namespace gw
