// current_wall_vertex, wall_distance_among_at, triangles_near_at, wall_distance_at, wall_point_velocity
// (engine/scene/moving_wall.hpp): the lazily evaluated current shape of a moving wall.
#include "engine/scene/moving_wall.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/scene/closest_point_triangle.hpp"
#include "engine/scene/nearest_face.hpp"

namespace gw {

namespace {

// The current corners, unit normal and bounding sphere of face f (make_vessel_scene's formulas, bit for
// bit). A time's faces are kept in a dense pool in the order they were first asked for, found through one
// 8-byte key per mesh face (epoch, pool slot): a sub-step's queries touch faces scattered over the whole
// mesh, and their cost was mostly cache misses.
struct Face {
  Eigen::Vector3d a, b, c, n, centre;
  double radius;
};
// A current vertex position, its rest position and its stamps in one cache line.
struct Vertex {
  Eigen::Vector3d x, rest;
  int stamp = 0, normal_stamp = 0;
};

// Current vertex positions and vertex normals of one (motion, time), computed on first use. Per thread,
// so concurrent episodes never share it; a pure accelerator (the same values without it). A sub-step
// asks for three times in turn (its start, its middle, its end = the next start): three slots.
struct CurrentWallCache {
  long id = -1;
  double t = std::numeric_limits<double>::quiet_NaN();
  int epoch = 0;
  long used = 0;
  WallTime at;
  std::vector<Vertex> v;
  std::vector<Eigen::Vector3d> n;
  std::vector<std::uint64_t> face_key;  // per mesh face: epoch << 32 | slot in `faces`
  std::vector<Face> faces;              // the pool (sized to the mesh once: never reallocated)
  std::size_t faces_used = 0;
};

CurrentWallCache& cache_for(const VesselScene& s, double t) {
  thread_local CurrentWallCache slots[3];
  thread_local long clock = 0;
  const WallMotion& m = *s.motion;
  ++clock;
  for (CurrentWallCache& c : slots)
    if (c.id == m.id && c.t == t) {
      c.used = clock;
      return c;
    }
  CurrentWallCache* oldest = &slots[0];
  for (CurrentWallCache& c : slots)
    if (c.used < oldest->used) oldest = &c;
  CurrentWallCache& c = *oldest;
  if (static_cast<int>(c.v.size()) != m.vertices || c.faces.size() != static_cast<std::size_t>(s.mesh.F.rows()) ||
      c.epoch == std::numeric_limits<int>::max()) {
    c.v.assign(m.vertices, Vertex{});
    for (int i = 0; i < m.vertices; ++i) c.v[i].rest = s.mesh.V.row(i).transpose();
    c.n.resize(m.vertices);
    c.face_key.assign(s.mesh.F.rows(), 0);
    c.faces.resize(s.mesh.F.rows());
    c.epoch = 0;
  }
  ++c.epoch;
  c.faces_used = 0;
  c.id = m.id;
  c.t = t;
  c.at = wall_time(m, t);
  c.used = clock;
  return c;
}

const Eigen::Vector3d& vertex(CurrentWallCache& c, const VesselScene& s, int i) {
  Vertex& v = c.v[i];
  if (v.stamp != c.epoch) {
    // The rest position from the record (rest.V is stored column by column: three cache lines).
    v.x = s.motion->kind == WallMotionKind::phases ? wall_vertex_position(*s.motion, s.mesh, i, c.at)
                                                   : wall_field_position(*s.motion, v.rest, c.at);
    v.stamp = c.epoch;
  }
  return v.x;
}


const Face& face(CurrentWallCache& cache, const VesselScene& s, int f) {
  std::uint64_t& key = cache.face_key[f];
  if ((key >> 32) == static_cast<std::uint64_t>(cache.epoch)) return cache.faces[key & 0xffffffffu];
  const std::size_t slot = cache.faces_used++;
  key = (static_cast<std::uint64_t>(cache.epoch) << 32) | slot;
  Face& r = cache.faces[slot];
  const std::array<int, 3>& corners = s.motion->face_vertices[f];
  r.a = vertex(cache, s, corners[0]);
  r.b = vertex(cache, s, corners[1]);
  r.c = vertex(cache, s, corners[2]);
  const Eigen::Vector3d n = (r.b - r.a).cross(r.c - r.a);
  const double len = n.norm();
  r.n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
  r.centre = (r.a + r.b + r.c) / 3.0;
  // One square root: sqrt is monotonic and correctly rounded, so this is the largest of the three norms.
  r.radius = std::sqrt(std::max({(r.a - r.centre).squaredNorm(), (r.b - r.centre).squaredNorm(),
                                 (r.c - r.centre).squaredNorm()}));
  return r;
}

// Angle-weighted vertex normal of the current shape (as make_vessel_scene computes it).
const Eigen::Vector3d& vertex_normal(CurrentWallCache& c, const VesselScene& s, int i) {
  if (c.v[i].normal_stamp == c.epoch) return c.n[i];
  const WallMotion& m = *s.motion;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = m.vertex_face_begin[i]; k < m.vertex_face_begin[i + 1]; ++k) {
    const int f = m.vertex_face[k], corner = m.vertex_corner[k];
    const Face& fd = face(c, s, f);
    const std::array<int, 3>& corners = m.face_vertices[f];
    const Eigen::Vector3d p0 = vertex(c, s, corners[corner]), p1 = vertex(c, s, corners[(corner + 1) % 3]),
                          p2 = vertex(c, s, corners[(corner + 2) % 3]);
    const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
    const double den = e1.norm() * e2.norm();
    const double angle = den > 0 ? std::acos(std::clamp(e1.dot(e2) / den, -1.0, 1.0)) : 0.0;
    sum += angle * fd.n;
  }
  const double len = sum.norm();
  if (len > 0) sum /= len;
  c.n[i] = sum;
  c.v[i].normal_stamp = c.epoch;
  return c.n[i];
}

}  // namespace

Eigen::Vector3d current_wall_vertex(const VesselScene& scene, int vertex_index, double t) {
  return vertex(cache_for(scene, t), scene, vertex_index);
}

WallDistance wall_distance_among_at(const VesselScene& scene, double t, const Eigen::Vector3d& p,
                                    const std::vector<int>& triangles, double cutoff,
                                    const std::vector<double>* lower_bounds, double moved, int* hint,
                                    const RestPoint* rest, const std::vector<Eigen::Vector4d>* rest_spheres) {
  CurrentWallCache& cache = cache_for(scene, t);
  NearestFace best(cutoff);
  double best_reach = std::sqrt(best.d2 * (1 + 1e-12));  // a current bounding sphere farther: skipped
  // Rest frame: every triangle with a current point within `reach_of` the best distance (plus the tie
  // tolerance of NearestFace) has its rest point within `rest_limit` of rest->X.
  auto reach_of = [&](double d2) { return rest_reach(*rest, std::sqrt(d2 + 2e-12 * (1 + d2))); };
  double rest_limit = rest ? reach_of(best.d2) : 0.0;
  auto consider = [&](int position) {
    const int f = triangles[position];
    if (rest) {
      const Eigen::Vector4d& sphere = rest_spheres ? (*rest_spheres)[position] : scene.face_spheres[f];
      // Cannot be nearer than the best (compared squared: no square root per triangle).
      const double rest_sphere_reach = rest_limit + sphere[3];
      if ((rest->X - sphere.head<3>()).squaredNorm() > rest_sphere_reach * rest_sphere_reach) return;
    }
    const Face& fd = face(cache, scene, f);
    const double sphere_reach = fd.radius + best_reach;
    if ((p - fd.centre).squaredNorm() > sphere_reach * sphere_reach) return;
    int region = 0;
    const Eigen::Vector3d c = closest_point_on_triangle(p, fd.a, fd.b, fd.c, region);
    const Eigen::Vector3d diff = p - c;
    if (best.offer(f, position, c, diff, diff.squaredNorm(), fd.n)) {
      best_reach = std::sqrt(best.d2 * (1 + 1e-12));
      if (rest) rest_limit = reach_of(best.d2);
    }
  };
  const int first = hint ? *hint : -1;
  if (first >= 0 && first < static_cast<int>(triangles.size())) consider(first);
  if (lower_bounds && rest) {
    // Rest frame, in two passes with the same answer as one: first the triangles whose rest bounding
    // sphere comes within the reach of the best so far (a sequential pass over the list), their records
    // prefetched; then those in list order as the single pass would take them (the reach only shrinks,
    // so every triangle the single pass would evaluate is among them). The current faces and vertices
    // are scattered over the mesh: asked for together, their cache misses overlap.
    thread_local std::vector<int> near;
    near.clear();
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      if ((*lower_bounds)[i] - moved > rest_limit) break;  // sorted: nothing later is closer
      const Eigen::Vector4d& sphere = rest_spheres ? (*rest_spheres)[i] : scene.face_spheres[triangles[i]];
      const double reach = rest_limit + sphere[3];
      if (static_cast<int>(i) == first || (rest->X - sphere.head<3>()).squaredNorm() > reach * reach) continue;
      near.push_back(static_cast<int>(i));
      __builtin_prefetch(&cache.face_key[triangles[i]]);
      __builtin_prefetch(&scene.motion->face_vertices[triangles[i]]);
    }
    for (const int i : near) {
      if ((*lower_bounds)[i] - moved > rest_limit) break;
      consider(i);
    }
  } else {
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      if (lower_bounds) {
        const double lb = (*lower_bounds)[i] - moved;
        if (lb > 0 && lb * lb > best.d2 * (1 + 1e-9) + 1e-18) break;  // sorted: nothing later is closer
      }
      if (static_cast<int>(i) != first) consider(static_cast<int>(i));
    }
  }
  if (hint) *hint = best.position;
  if (best.triangle < 0) return to_wall_distance(best, p, p, p, [](int) { return Eigen::Vector3d::Zero(); });
  const std::array<int, 3>& corners = scene.motion->face_vertices[best.triangle];
  return to_wall_distance(best, vertex(cache, scene, corners[0]), vertex(cache, scene, corners[1]),
                          vertex(cache, scene, corners[2]),
                          [&](int k) -> Eigen::Vector3d { return vertex_normal(cache, scene, corners[k]); });
}

bool wall_rest_point_at(const VesselScene& scene, double t, const Eigen::Vector3d& p, const Eigen::Vector3d* guess,
                        RestPoint& out) {
  return wall_rest_point(*scene.motion, p, cache_for(scene, t).at, guess, out);
}

void triangles_near_at(const VesselScene& scene, double t, const Eigen::Vector3d& p, double radius,
                       std::vector<int>& out, std::vector<double>* sphere_distances) {
  Eigen::Vector3d centre;
  double rest_radius = 0;
  rest_query_ball(*scene.motion, p, radius, t, centre, rest_radius);
  grid_candidates(*scene.grid, centre, rest_radius, out);
  CurrentWallCache& cache = cache_for(scene, t);
  if (sphere_distances) sphere_distances->clear();
  std::size_t kept = 0;
  for (const int f : out) {
    const Eigen::Vector4d& rest = scene.face_spheres[f];
    if ((centre - rest.head<3>()).norm() - rest[3] > rest_radius) continue;  // cannot come near p
    const Face& fd = face(cache, scene, f);
    const double d = (p - fd.centre).norm() - fd.radius;
    if (d > radius) continue;
    out[kept++] = f;
    if (sphere_distances) sphere_distances->push_back(d);
  }
  out.resize(kept);
}

WallDistance wall_distance_at(const VesselScene& scene, double t, const Eigen::Vector3d& p) {
  // An upper bound of the current distance: the current distance to the triangle nearest to p's
  // pre-image on the rest mesh; then every triangle whose current bounding sphere is that near.
  Eigen::Vector3d centre;
  double unused = 0;
  rest_query_ball(*scene.motion, p, 0, t, centre, unused);
  int tri = -1;
  nearest_triangle(scene, centre, tri);
  double upper = std::numeric_limits<double>::infinity();
  if (tri >= 0) {
    CurrentWallCache& cache = cache_for(scene, t);
    const Face& fd = face(cache, scene, tri);
    int region = 0;
    upper = (p - closest_point_on_triangle(p, fd.a, fd.b, fd.c, region)).norm();
  }
  if (!std::isfinite(upper)) upper = 1e6;
  std::vector<int> cand;
  triangles_near_at(scene, t, p, upper + 1e-6 + 1e-9 * (1 + upper), cand);
  return wall_distance_among_at(scene, t, p, cand, upper + 1e-3 + 1e-6 * upper);
}

Eigen::Vector3d wall_point_velocity(const VesselScene& scene, int triangle, const Eigen::Vector3d& closest, double t,
                                    double h) {
  CurrentWallCache& cache = cache_for(scene, t);
  const std::array<int, 3>& corners = scene.motion->face_vertices[triangle];
  const Eigen::Vector3d a = vertex(cache, scene, corners[0]), b = vertex(cache, scene, corners[1]),
                        c = vertex(cache, scene, corners[2]);
  const Eigen::Vector3d v0 = b - a, v1 = c - a, v2 = closest - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  double wb = 1.0 / 3, wc = 1.0 / 3;
  if (den > 0) {
    wb = (d11 * d20 - d01 * d21) / den;
    wc = (d00 * d21 - d01 * d20) / den;
  }
  CurrentWallCache& end = cache_for(scene, t + h);  // (another slot: `cache` stays valid)
  const Eigen::Vector3d a1 = vertex(end, scene, corners[0]), b1 = vertex(end, scene, corners[1]),
                        c1 = vertex(end, scene, corners[2]);
  return ((1 - wb - wc) * (a1 - a) + wb * (b1 - b) + wc * (c1 - c)) / h;
}

}  // namespace gw
