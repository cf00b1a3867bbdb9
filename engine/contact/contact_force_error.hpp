#pragma once
// How far a contact solve's impulses are from a reference solve of the same contact problem (e.g. one run
// to convergence), measured where the wire feels them. Inputs: the contacts, the two impulse vectors
// (3 per contact: n, t1, t2, as ContactWorkspace::impulse) and the wire's node count. Output, each relative
// to the reference's total contact impulse sum_c |p_ref,c|:
//  - resultant: |sum_c f_c - sum_c f_ref,c| (the net force on the wire);
//  - peak_node: | max_i |F_i| - max_i |F_ref,i| | with F_i the force the contacts put on node i (the peak
//    node force that evaluate reports), here relative to max_i |F_ref,i| instead;
//  - distribution: sum_c |f_c - f_ref,c| (how the impulses are shared among the contact points; nearly
//    redundant points, e.g. a node and the midpoint beside it on a straight stretch, share a load in many
//    ways that give the wire the same forces).
// A reference with no contact impulse gives zeros.
#include <Eigen/Core>
#include <vector>

#include "engine/contact/detect_contacts.hpp"

namespace gw {

struct ContactForceError {
  double resultant = 0, peak_node = 0, distribution = 0;
  bool reference_converged = true;  // set by the caller: whether the reference solve met its tolerance
};

ContactForceError contact_force_error(const std::vector<ContactPoint>& contacts, const Eigen::VectorXd& impulse,
                                      const Eigen::VectorXd& reference, int nodes);

}  // namespace gw
