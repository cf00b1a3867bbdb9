#include "engine/wire/wire_queries.hpp"

#include <algorithm>
#include <stdexcept>

#include "engine/wire/so3.hpp"

namespace gw {

std::vector<Eigen::Vector3d> inserted_node_positions(const WireModel& model, const WireState& state) {
  const int k = first_free_node(model, state);
  return std::vector<Eigen::Vector3d>(state.x.begin() + k, state.x.end());
}

Eigen::Vector3d tip_position(const WireModel& model, const WireState& state) { return state.x[model.nodes - 1]; }

Eigen::Vector3d node_tangent(const WireState& state, int i) { return state.q[i] * Eigen::Vector3d::UnitX(); }

std::vector<Eigen::Vector3d> tip_tangents(const WireModel& model, const WireState& state, int count, double spacing_mm) {
  if (count < 1) throw std::invalid_argument("tip_tangents: count must be >= 1");
  if (!(spacing_mm >= 0)) throw std::invalid_argument("tip_tangents: spacing must be >= 0");
  std::vector<Eigen::Vector3d> out;
  out.reserve(count);
  int e = model.nodes - 2;  // element containing the current arc, walked proximally
  for (int j = 0; j < count; ++j) {
    const double s = std::min(j * spacing_mm, model.params.length_mm);
    while (e > 0 && model.arc_from_tip[e] < s) --e;
    // Element e spans arcs [arc[e+1], arc[e]] (measured from the tip).
    const double t = std::clamp((s - model.arc_from_tip[e + 1]) / model.length[e], 0.0, 1.0);
    const Eigen::Vector3d tan = (1 - t) * node_tangent(state, e + 1) + t * node_tangent(state, e);
    out.push_back(tan.normalized());
  }
  return out;
}

Eigen::Vector3d tip_curvature_vector(const WireModel& model, const WireState& state) {
  // Mean bending rate (Darboux vector) over the curved tip, crossed with the tangent at the tip: for a
  // circular tip this is exactly the curvature vector at the tip, and it averages out element noise.
  Eigen::Vector3d omega_sum = Eigen::Vector3d::Zero();
  double arc = 0;
  for (int e = model.nodes - 2; e >= 0 && arc < model.params.tip_length_mm - 1e-9; --e) {
    const Mat3 ra = state.q[e].toRotationMatrix();
    const Vec3 phi = so3_log(ra.transpose() * state.q[e + 1].toRotationMatrix());
    omega_sum += ra * phi;  // world-frame rotation over the element (the axis is the same in both frames)
    arc += model.length[e];
  }
  if (arc <= 0) return Eigen::Vector3d::Zero();
  return (omega_sum / arc).cross(node_tangent(state, model.nodes - 1));
}

Eigen::Vector3d tip_velocity(const WireModel& model, const WireState& state) { return state.v[model.nodes - 1]; }

}  // namespace gw
