#include "engine/wire/wire_state.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/wire/so3.hpp"

namespace gw {

Eigen::Quaterniond introducer_frame(const WireState& s) {
  return (Eigen::AngleAxisd(s.proximal_rotation_rad, s.direction) * s.base_frame).normalized();
}

WireState make_initial_state(const WireModel& model, const Eigen::Vector3d& inlet, const Eigen::Vector3d& direction,
                             double proximal_rotation_rad, double inserted_length_mm) {
  if (!(direction.norm() > 1e-12) || !direction.allFinite())
    throw std::runtime_error("make_initial_state: direction must be a non-zero finite vector");
  if (!inlet.allFinite()) throw std::runtime_error("make_initial_state: inlet must be finite");
  if (!std::isfinite(proximal_rotation_rad))
    throw std::runtime_error("make_initial_state: proximal rotation must be finite");
  if (!(inserted_length_mm >= 0) || !std::isfinite(inserted_length_mm))
    throw std::runtime_error("make_initial_state: inserted length must be >= 0 and finite");
  WireState s;
  const int n = model.nodes;
  s.inlet = inlet;
  s.direction = direction.normalized();
  s.base_frame = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), s.direction);
  s.inserted_length_mm = std::min(inserted_length_mm, model.params.length_mm);
  s.proximal_rotation_rad = proximal_rotation_rad;
  s.x.assign(n, Eigen::Vector3d::Zero());
  s.q.assign(n, Eigen::Quaterniond::Identity());
  s.v.assign(n, Eigen::Vector3d::Zero());
  s.w.assign(n, Eigen::Vector3d::Zero());
  s.external_force.assign(n, Eigen::Vector3d::Zero());
  s.external_torque.assign(n, Eigen::Vector3d::Zero());
  s.contact_force.assign(n, Eigen::Vector3d::Zero());
  place_held_nodes(model, s, 0.0, 0.0);
  // Free part in its rest shape: walk the elements from the clamp using rest chords and rotations.
  const int k = first_free_node(model, s);
  for (int i = k; i < n; ++i) {
    const int e = i - 1;
    const Mat3 ra = s.q[e].toRotationMatrix();
    const Mat3 rm = ra * so3_exp(0.5 * model.rest_phi[e]);
    s.x[i] = s.x[e] + rm * Vec3(model.chord[e], 0, 0);
    s.q[i] = Eigen::Quaterniond(ra * so3_exp(model.rest_phi[e])).normalized();
  }
  return s;
}

int first_free_node(const WireModel& model, const WireState& state) {
  int k = 1;
  while (k < model.nodes && model.arc_from_tip[k] >= state.inserted_length_mm) ++k;
  return k;
}

void place_held_nodes(const WireModel& model, WireState& s, double push, double rotate) {
  const int k = first_free_node(model, s);
  const Eigen::Quaterniond frame = introducer_frame(s);
  for (int i = 0; i < k; ++i) {
    s.x[i] = s.inlet + (s.inserted_length_mm - model.arc_from_tip[i]) * s.direction;
    s.q[i] = frame;
    s.v[i] = push * s.direction;
    s.w[i] = rotate * s.direction;
  }
}

}  // namespace gw
