#include "engine/contact/contact_force_error.hpp"

#include <algorithm>

namespace gw {

ContactForceError contact_force_error(const std::vector<ContactPoint>& contacts, const Eigen::VectorXd& impulse,
                                      const Eigen::VectorXd& reference, int nodes) {
  ContactForceError e;
  std::vector<Eigen::Vector3d> node(nodes, Eigen::Vector3d::Zero()), node_ref(nodes, Eigen::Vector3d::Zero());
  Eigen::Vector3d net = Eigen::Vector3d::Zero(), net_ref = Eigen::Vector3d::Zero();
  double total_ref = 0, moved = 0;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const ContactPoint& cp = contacts[c];
    const auto world = [&](const Eigen::VectorXd& p) -> Eigen::Vector3d {
      return cp.n * p[3 * c] + cp.t1 * p[3 * c + 1] + cp.t2 * p[3 * c + 2];
    };
    const Eigen::Vector3d f = world(impulse), f_ref = world(reference);
    net += f;
    net_ref += f_ref;
    total_ref += f_ref.norm();
    moved += (f - f_ref).norm();
    node[cp.node_a] += cp.wa * f;
    node_ref[cp.node_a] += cp.wa * f_ref;
    if (cp.node_b >= 0) {
      node[cp.node_b] += cp.wb * f;
      node_ref[cp.node_b] += cp.wb * f_ref;
    }
  }
  if (total_ref <= 0) return e;
  double peak = 0, peak_ref = 0;
  for (int i = 0; i < nodes; ++i) {
    peak = std::max(peak, node[i].norm());
    peak_ref = std::max(peak_ref, node_ref[i].norm());
  }
  e.resultant = (net - net_ref).norm() / total_ref;
  e.peak_node = peak_ref > 0 ? std::abs(peak - peak_ref) / peak_ref : 0;
  e.distribution = moved / total_ref;
  return e;
}

}  // namespace gw
