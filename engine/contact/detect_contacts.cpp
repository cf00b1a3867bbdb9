#include "engine/contact/detect_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/scene/moving_wall.hpp"
#include "engine/scene/wall_distance_by_grid.hpp"

namespace gw {

int contact_point_count(const WireModel& model) { return 2 * model.nodes - 1; }

Eigen::Vector3d contact_point_position(const WireModel& model, const std::vector<Eigen::Vector3d>& x, int point) {
  if (point < model.nodes) return x[point];
  const int e = point - model.nodes;
  return 0.5 * (x[e] + x[e + 1]);
}

bool contact_point_active(const WireModel& model, const WireState& state, int point) {
  const double arc = point < model.nodes
                         ? model.arc_from_tip[point]
                         : 0.5 * (model.arc_from_tip[point - model.nodes] + model.arc_from_tip[point - model.nodes + 1]);
  return arc < state.inserted_length_mm - model.params.inlet_clearance_mm;
}

namespace {

const double kMidpointMinLength = 1.0;  // mm

// Re-gathers the candidates of one point around `p` within `radius`, sorted by distance lower bound.
// A moving wall: its shape at time t (the bounds then hold at t).
// `rest_frame`: a moving wall's list kept in the rest configuration, gathered around the pre-image p on
// the rest mesh exactly as a static wall's (see cached_wall_distance).
void refresh(const VesselScene& scene, const Eigen::Vector3d& p, double radius, WallCandidates& c, double t,
             bool rest_frame = false) {
  c.centre = p;
  c.gathered = radius;
  c.closest = -1;
  c.rest = rest_frame;
  const bool moving = scene.motion && !rest_frame;  // lists on the current shape at t
  if (moving) {
    thread_local std::vector<double> spheres;
    triangles_near_at(scene, t, p, radius, c.triangles, &spheres);
    c.wall_time = t;
    c.lower_bounds.resize(c.triangles.size());
    for (std::size_t i = 0; i < c.triangles.size(); ++i) c.lower_bounds[i] = std::max(0.0, spheres[i]);
  } else {
    triangles_near(scene, p, radius, c.triangles);
  }
  const std::size_t n = c.triangles.size();
  c.lower_bounds.resize(n);
  for (std::size_t i = 0; i < n && !moving; ++i) {
    const int f = c.triangles[i];
    const Eigen::Vector4d& sphere = scene.face_spheres[f];
    c.lower_bounds[i] = std::max(0.0, (p - sphere.head<3>()).norm() - sphere[3]);
  }
  // Sort both arrays by the lower bound (ties by triangle: deterministic), through per-thread scratch.
  thread_local std::vector<std::pair<double, int>> order;
  order.resize(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = {c.lower_bounds[i], c.triangles[i]};
  std::sort(order.begin(), order.end());
  for (std::size_t i = 0; i < n; ++i) {
    c.lower_bounds[i] = order[i].first;
    c.triangles[i] = order[i].second;
  }
  // Scanned with the list, not through the scene's arrays (cache misses).
  c.rest_spheres.clear();
  c.face_bounds.clear();
  if (rest_frame)
    for (std::size_t i = 0; i < n; ++i) c.rest_spheres.push_back(scene.face_spheres[c.triangles[i]]);
  else if (!moving)
    for (std::size_t i = 0; i < n; ++i) {
      c.face_bounds.push_back(scene.face_spheres[c.triangles[i]]);
      c.face_bounds.push_back(scene.face_planes[c.triangles[i]]);
    }
  if (n == 0) {
    // No wall within `radius`: the point may move until it could be within reach of the wall.
    c.clearance = moving ? wall_distance_at(scene, t, p).signed_distance
                         : wall_distance_by_grid(scene, p, radius).signed_distance;
    c.gathered = std::max(radius, std::abs(c.clearance));
  }
}

// The cache entry of contact point `point`; the cache is (re)made first when the scene or the number of
// points changed.
WallCandidates& cache_entry(const WireModel& model, const VesselScene& scene, WireState& state, int point) {
  const int count = contact_point_count(model);
  if (state.wall_cache_scene != &scene || static_cast<int>(state.wall_cache.size()) != count) {
    state.wall_cache.assign(count, WallCandidates{});
    state.wall_cache_scene = &scene;
  }
  return state.wall_cache[point];
}

// Keeps `bound` (exact, or a lower bound) as the signed wall distance at p and wall time t (the Lipschitz
// test of the next query).
inline void keep_bound(WallCandidates& c, const Eigen::Vector3d& p, double bound, double t) {
  c.bound_point = p;
  c.bound = bound;
  c.bound_time = t;
}

// Rigid and cardiac walls: sets `out` to the distance at p (wall time t) from the list kept in the REST
// frame and returns true; false (out untouched) when p has no usable pre-image (current_frame_distance then).
bool rest_frame_distance(const WireModel& model, const VesselScene& scene, WallCandidates& c,
                         const Eigen::Vector3d& p, double need, double cutoff, double t, WallDistance& out) {
  // The list lives in the REST configuration, around the point's pre-image X
  // (wall_rest_point_at: Newton from the last one), gathered from the rest grid with rest bounding
  // spheres, as a static wall's. Exactness: a current triangle point within `need` of p has its rest
  // point within rest_reach(need) of X (wall_motion.hpp: the map's smallest stretch sigma, curvature K
  // and the inversion residual), hence within rest_reach(need) + |X - centre| of the list's centre; the
  // list holds every triangle whose rest bounding sphere comes that near while that sum stays below
  // `gathered`. The heart's beat does not move X (a wall point keeps its rest point); only the wire's
  // motion relative to the wall does, so a list is re-gathered about as often as on a static wall.
  RestPoint rp;
  const bool warm = c.rest && c.gathered >= 0;
  if (!wall_rest_point_at(scene, t, p, warm ? &c.rest_point : nullptr, rp)) return false;
  const double reach = rest_reach(rp, need);
  if (!std::isfinite(reach)) return false;
  c.rest_point = rp.X;
  double moved = warm ? (rp.X - c.centre).norm() : 0;
  if (!warm || reach + moved > c.gathered) {
    const double radius = rest_reach(rp, need + model.params.contact_slack_mm);
    refresh(scene, rp.X, std::isfinite(radius) ? radius : reach, c, t, true);
    moved = 0;
  }
  if (c.triangles.empty()) {
    // No triangle's rest sphere within `gathered` of the centre: X is on the centre's side of the
    // rest wall (inside or outside, kept by the map) and nothing comes within `need` of p.
    if (c.clearance < 0) {  // outside: exact
      out = wall_distance_at(scene, t, p);
      return true;
    }
    WallDistance far;
    far.signed_distance = std::max(need, current_reach(rp, c.gathered - moved));  // lower bound, >= need
    keep_bound(c, p, far.signed_distance, t);
    out = far;
    return true;
  }
  WallDistance wd =
      wall_distance_among_at(scene, t, p, c.triangles, cutoff, &c.lower_bounds, moved, &c.closest, &rp,
                             &c.rest_spheres);
  if (wd.triangle < 0) wd.signed_distance = cutoff;  // nothing within the cutoff: well inside
  keep_bound(c, p, wd.signed_distance, t);
  out = wd;
  return true;
}

// Static walls, phase-sampled walls and the fallback of the rest frame: the distance at p (wall time t)
// from the list on the wall's current shape, re-gathered when p moved (or the wall travelled) too far.
WallDistance current_frame_distance(const WireModel& model, const VesselScene& scene, WallCandidates& c,
                                    const Eigen::Vector3d& p, double need, double cutoff, double t) {
  const WallMotion* motion = scene.motion.get();
  double moved = c.gathered >= 0 ? (p - c.centre).norm() : 0;
  if (motion && c.gathered >= 0) moved += wall_max_travel(*motion, c.wall_time, t);
  if (c.gathered < 0 || c.rest || c.gathered - moved < need) {
    refresh(scene, p, need + model.params.contact_slack_mm, c, t);
    moved = 0;
  }
  if (c.triangles.empty()) {
    if (c.clearance < 0)  // outside: exact
      return motion ? wall_distance_at(scene, t, p) : wall_distance_by_grid(scene, p, need);
    WallDistance far;
    far.signed_distance = c.clearance - moved;  // lower bound, >= need
    keep_bound(c, p, far.signed_distance, t);
    return far;
  }
  WallDistance wd = motion ? wall_distance_among_at(scene, t, p, c.triangles, cutoff, &c.lower_bounds, moved, &c.closest)
                           : wall_distance_among(scene, p, c.triangles, cutoff, &c.lower_bounds, moved, &c.closest,
                                                 &c.face_bounds);
  if (wd.triangle < 0) wd.signed_distance = cutoff;  // nothing within the cutoff: well inside
  keep_bound(c, p, wd.signed_distance, t);  // exact, or (triangle < 0) a lower bound
  return wd;
}

}  // namespace

WallDistance cached_wall_distance(const WireModel& model, const VesselScene& scene, WireState& state, int point,
                                  const Eigen::Vector3d& p, double need, bool exact_to_cutoff, double time) {
  WallCandidates& c = cache_entry(model, scene, state, point);
  // Only distances below `cutoff` matter: contacts need `need`, the divergence check needs to see a
  // point that is more than the divergence margin outside. Farther triangles are not scanned.
  const double cutoff = std::max(need, model.params.divergence_margin_mm + model.radius_mm);
  // Deeper inside than needed by the Lipschitz bound: no scan (most points of a wire in a wide lumen).
  // A moving wall: the bounds measured at earlier wall times lose the wall's largest travel since.
  const WallMotion* motion = scene.motion.get();
  const double t = motion ? (std::isnan(time) ? state.time : time) : 0.0;
  double deep = c.bound - (p - c.bound_point).norm();
  if (motion) deep -= wall_max_travel(*motion, c.bound_time, t);
  if (deep > (exact_to_cutoff ? cutoff : need)) {
    WallDistance far;
    far.signed_distance = deep;  // lower bound, > need
    return far;
  }
  WallDistance from_rest;
  if (motion && motion->kind != WallMotionKind::phases &&
      rest_frame_distance(model, scene, c, p, need, cutoff, t, from_rest))
    return from_rest;
  return current_frame_distance(model, scene, c, p, need, cutoff, t);
}

namespace {

// The nearest wall of another side than `inward` (the inward normal of the nearest wall) for contact point
// `point` at p, within `reach`, wall time t: among the triangles within reach (the point's static list, or a
// moving wall's current shape gathered afresh), those whose inward face normal turns from `inward` by more
// than 60 degrees, scanned for the nearest as every query is; its smooth normal is checked again. triangle
// -1: none.
WallDistance other_wall_side(const VesselScene& scene, const WireState& state, int point, const Eigen::Vector3d& p,
                             const Eigen::Vector3d& inward, double reach, double t) {
  thread_local std::vector<int> near, other;
  other.clear();
  WallDistance wd;
  if (scene.motion) {
    const auto& F = scene.mesh.F;
    triangles_near_at(scene, t, p, reach, near);
    for (const int f : near) {
      const Eigen::Vector3d a = current_wall_vertex(scene, F(f, 0), t), b = current_wall_vertex(scene, F(f, 1), t),
                            c = current_wall_vertex(scene, F(f, 2), t);
      const Eigen::Vector3d n = (b - a).cross(c - a);  // outward (counter-clockwise seen from outside)
      if (!same_wall_side(inward, -n.normalized())) other.push_back(f);
    }
    wd = wall_distance_among_at(scene, t, p, other, reach);
  } else {
    const WallCandidates& c = state.wall_cache[point];
    const double moved = (p - c.centre).norm();
    for (std::size_t i = 0; i < c.triangles.size(); ++i) {
      if (c.lower_bounds[i] - moved > reach) break;  // sorted
      const int f = c.triangles[i];
      if (!same_wall_side(inward, -scene.face_normals.row(f).transpose())) other.push_back(f);
    }
    wd = wall_distance_among(scene, p, other, reach);
  }
  if (wd.triangle >= 0 && same_wall_side(inward, wd.inward)) wd.triangle = -1;  // its smooth normal
  return wd;
}

}  // namespace

bool same_wall_side(const Eigen::Vector3d& start_normal, const Eigen::Vector3d& mid_normal) {
  return start_normal.dot(mid_normal) >= 0.5;  // cos 60 degrees
}

void detect_contacts(const WireModel& model, const VesselScene& scene, WireState& state,
                     const std::vector<Eigen::Vector3d>& v_free, double h, std::vector<ContactPoint>& out,
                     double& deepest) {
  out.clear();
  deepest = 0;
  const double r = model.radius_mm;
  const double margin = model.params.contact_margin_mm;
  const double dt = h;
  const int first_free = first_free_node(model, state);
  // Active points are a suffix of the nodes and a suffix of the midpoints (arc decreases distally).
  int first_node = model.nodes, first_mid = model.nodes - 1;
  while (first_node > first_free && contact_point_active(model, state, first_node - 1)) --first_node;
  while (first_mid > first_free && contact_point_active(model, state, model.nodes + first_mid - 1)) --first_mid;
  const double wall_travel = scene.motion ? wall_max_travel(*scene.motion, state.time, state.time + dt) : 0.0;
  auto visit = [&](int point) {
    ContactPoint c;
    c.point = point;
    if (point < model.nodes) {
      c.node_a = point;
    } else {
      c.node_a = point - model.nodes;
      c.node_b = c.node_a + 1;
      c.wa = c.wb = 0.5;
    }
    Eigen::Vector3d v = c.wa * v_free[c.node_a];
    if (c.node_b >= 0) v += c.wb * v_free[c.node_b];
    // Swept test: the point is a candidate if its free motion this step could bring it within the margin
    // (or, a moving wall, the wall's own travel this step could).
    double reach = r + margin + dt * v.norm();
    if (scene.motion) reach += wall_travel;
    const Eigen::Vector3d p = contact_point_position(model, state.x, point);
    const WallDistance wd = cached_wall_distance(model, scene, state, point, p, reach);
    deepest = std::max(deepest, -wd.signed_distance);
    if (!(wd.signed_distance < reach) || wd.triangle < 0) return;
    if (scene.motion) c.v_wall = wall_point_velocity(scene, wd.triangle, wd.closest, state.time, dt);
    c.n = wd.inward;
    c.t1 = c.n.unitOrthogonal();
    c.t2 = c.n.cross(c.t1);
    c.gap = wd.signed_distance - r;
    c.v_free = v;
    out.push_back(c);
    if (c.gap >= -kCreaseDepthMm) return;
    const WallDistance other = other_wall_side(scene, state, point, p, c.n, reach, state.time);
    if (other.triangle < 0 || !(other.signed_distance < reach)) return;
    if (scene.motion) c.v_wall = wall_point_velocity(scene, other.triangle, other.closest, state.time, dt);
    c.side = 1;
    c.n = other.inward;
    c.t1 = c.n.unitOrthogonal();
    c.t2 = c.n.cross(c.t1);
    c.gap = other.signed_distance - r;
    out.push_back(c);
  };
  for (int i = first_node; i < model.nodes; ++i) visit(i);
  // Midpoints only where an element is long enough for its chord to cut a bend of the wall noticeably
  // (sagitta l^2 / 8R): the 2 mm body elements, not the 0.5 mm tip elements.
  for (int e = first_mid; e + 1 < model.nodes; ++e)
    if (model.length[e] > kMidpointMinLength) visit(model.nodes + e);
}

}  // namespace gw
