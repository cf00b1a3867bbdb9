#include "task/wall_force.hpp"

#include <algorithm>

namespace gw {

WallForce wall_force(const WireModel& model, const WireState& state) {
  WallForce f;
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  const std::size_t n = std::min(state.contact_force.size(), model.arc_from_tip.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double magnitude = state.contact_force[i].norm();
    f.peak_node_mN = std::max(f.peak_node_mN, magnitude);
    f.total_mN += magnitude;
    if (model.arc_from_tip[i] <= kTipForceLengthMm + 1e-9) tip += state.contact_force[i];
  }
  f.tip_mN = tip.norm();
  return f;
}

}  // namespace gw
