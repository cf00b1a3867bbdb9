#include "engine/contact/detect_contacts.hpp"

#include <cmath>
#include <limits>

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

WallDistance cached_wall_distance(const WireModel& model, const VesselScene& scene, WireState& state, int point,
                                  const Eigen::Vector3d& p) {
  const int count = contact_point_count(model);
  if (state.wall_cache_scene != &scene || static_cast<int>(state.wall_cache.size()) != count) {
    state.wall_cache.assign(count, WallCandidates{});
    state.wall_cache_scene = &scene;
  }
  WallCandidates& c = state.wall_cache[point];
  const double reach = model.radius_mm + model.params.contact_margin_mm;
  if (!(c.slack >= 0) || (p - c.centre).squaredNorm() > c.slack * c.slack) {
    const double slack = model.params.contact_slack_mm;
    triangles_within(scene, p, reach + slack, c.triangles);
    c.centre = p;
    if (!c.triangles.empty()) {
      c.slack = slack;
    } else {
      // Nothing within reach + slack: remember how far the wall is and on which side, so the point
      // can move that far before asking again.
      const WallDistance exact = wall_distance(scene, p);
      c.clearance = exact.signed_distance;
      c.slack = std::abs(exact.signed_distance) - reach;
      if (exact.signed_distance < 0) {
        c.slack = -1;  // outside the vessel: never trust a cache, report the exact distance
        return exact;
      }
    }
  }
  if (c.triangles.empty()) {
    WallDistance far;
    far.signed_distance = c.clearance - (p - c.centre).norm();  // a lower bound, still beyond reach
    return far;
  }
  WallDistance wd = wall_distance_among(scene, p, c.triangles, reach + c.slack);
  if (wd.triangle < 0) wd.signed_distance = reach + 1.0;  // every candidate beyond reach
  return wd;
}

void detect_contacts(const WireModel& model, const VesselScene& scene, WireState& state,
                     const std::vector<Eigen::Vector3d>& x, std::vector<ContactPoint>& out) {
  out.clear();
  const double r = model.radius_mm;
  const double margin = model.params.contact_margin_mm;
  // Active points are a suffix of the nodes and a suffix of the midpoints (arc decreases distally).
  int first_node = model.nodes, first_mid = model.nodes - 1;
  while (first_node > 0 && contact_point_active(model, state, first_node - 1)) --first_node;
  while (first_mid > 0 && contact_point_active(model, state, model.nodes + first_mid - 1)) --first_mid;
  const int first_free = first_free_node(model, state);
  auto visit = [&](int point) {
    // A midpoint whose proximal node is still in the introducer is held there.
    if (point >= model.nodes && point - model.nodes < first_free) return;
    if (point < first_free) return;
    const Eigen::Vector3d p = contact_point_position(model, x, point);
    const WallDistance wd = cached_wall_distance(model, scene, state, point, p);
    const double gap = wd.signed_distance - r;
    if (!(gap < margin) || wd.triangle < 0) return;
    ContactPoint c;
    c.point = point;
    if (point < model.nodes) {
      c.node_a = point;
    } else {
      c.node_a = point - model.nodes;
      c.node_b = c.node_a + 1;
      c.wa = c.wb = 0.5;
    }
    c.n = wd.inward;
    c.t1 = c.n.unitOrthogonal();
    c.t2 = c.n.cross(c.t1);
    c.gap = gap;
    out.push_back(c);
  };
  for (int i = first_node; i < model.nodes; ++i) visit(i);
  for (int e = first_mid; e + 1 < model.nodes; ++e) visit(model.nodes + e);
}

}  // namespace gw
