#pragma once
// Stage "constraints": Lagrange-multiplier contact with Coulomb friction (paper Eq. 2).
// With the free-motion velocity change dv_free of the implicit step, the correction is
// dv_c = A^-1 H^T p (p = dt lambda, impulses); the gaps become g + dt (W p)_n with the compliance
// W = H A^-1 H^T. Projected Gauss-Seidel solves
//   0 <= p_n  _|_  (W p)_n + g / dt >= 0,      |p_t| <= mu p_n opposing the tangential velocity.
// W is built from the block-tridiagonal factorisation: selected blocks of A^-1 between contact nodes,
// chained through the G factors, O(N + n_c^2) instead of one solve per constraint.
#include <Eigen/Core>
#include <vector>

#include "engine/contact/detect_contacts.hpp"
#include "engine/solver/block_tridiagonal.hpp"

namespace gw {

struct ContactWorkspace {
  std::vector<Mat6> sigma;           // diagonal blocks of A^-1
  std::vector<int> nodes;            // sorted unique local nodes touched by contacts
  std::vector<int> slot;             // local node -> index in `nodes` (-1 if none)
  std::vector<Mat6> chain;           // products of -G between consecutive contact nodes
  std::vector<Eigen::Matrix3d> xtt;  // translational blocks of A^-1 between contact nodes (dense)
  Eigen::MatrixXd w;                 // compliance, 3 rows per contact
  Eigen::VectorXd bias, impulse, h_t_p;
};

struct ContactSolveResult {
  int iterations = 0;
  double residual = 0;  // largest impulse change in the last sweep, relative to the largest impulse
};

// Solves for the contact impulses and adds the velocity correction to `dv` (6 per free node).
// `v_free`: predicted world velocity of each contact point without contact; `first_free`: global index of
// local node 0. Writes impulses per contact (3 each: n, t1, t2) into ws.impulse.
ContactSolveResult solve_contacts(const BlockTridiagonal& a, const BlockTridiagonalFactor& f, int first_free,
                                  const std::vector<ContactPoint>& contacts,
                                  const std::vector<Eigen::Vector3d>& v_free, double dt, double mu, int iterations,
                                  ContactWorkspace& ws, Eigen::Ref<Eigen::VectorXd> dv);

}  // namespace gw
