#pragma once
// Stage "constraints": Lagrange-multiplier contact with Coulomb friction (paper Eq. 2).
// With the free-motion velocities v_free of the implicit step, the correction is dv_c = A^-1 H^T p
// (p = dt lambda, impulses) and the contact velocities become u = H v_free + W p with the compliance
// W = H A^-1 H^T. Projected Gauss-Seidel solves
//   0 <= p_n  _|_  g / dt + u_n >= 0,      |p_t| <= mu p_n, sticking (u_t = 0) inside the cone.
// W is built from the block-tridiagonal factorisation: selected blocks of A^-1 between contact nodes,
// chained through the G factors, instead of one solve per constraint. Only the columns of contacts
// whose impulse moves are built (most contacts found by the swept margin never press): O(N) plus
// O(n_c) per pressing contact, instead of O(N + n_c^2).
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
  std::vector<Eigen::Matrix3d> xtt;  // translational blocks of A^-1 between contact nodes (k x k)
  std::vector<char> x_built;         // per contact node: its row and column of xtt are filled
  Eigen::MatrixXd w;                 // compliance, 3 rows per contact; only the built columns are valid
  std::vector<Eigen::Matrix3d> w_diag;  // diagonal blocks of W, one per contact
  std::vector<char> column_built;    // per contact: its column block of W is in `w`
  Eigen::VectorXd bias, impulse, h_t_p;  // h_t_p: after contact_velocity_change, A^-1 H^T p
  Eigen::VectorXd u;                 // contact velocities W p + bias during the solve
  int first_free = 0;
  std::vector<Eigen::Matrix3d> basis;  // per contact rows (n, t1, t2)
  // Friction lever arm [mm] (set by the caller before prepare_contact_compliance): 0, the paper's model,
  // friction acts at the wire's axis (H touches translations only); r > 0, at the wire surface on the
  // wall side, p = x - r n, so a tangent row t of H is (t^T, -r (n x t)^T) on (v, w): the surface point
  // moves with v + w x (-r n), and the friction impulse p_t there gives the node the torque -r n x p_t.
  double lever = 0;
  std::vector<Mat6> x66;             // with a lever: full 6x6 blocks of A^-1 between contact nodes (k x k)
  std::vector<Eigen::Matrix<double, 3, 6>> jac;  // with a lever: per contact rows of H on one node's (v, w)
};

struct ContactSolveResult {
  int iterations = 0;
  double residual = 0;  // largest impulse change in the last sweep, relative to the largest impulse
};

// The sweeps stop when the last one changed no impulse by more than this, relative to the largest impulse;
// a solve whose residual is still above it stopped at its sweep cap.
constexpr double kContactSweepTolerance = 1e-6;

// Step 1: the blocks of A^-1 between the contact nodes (independent of the contact directions).
void prepare_contact_compliance(const BlockTridiagonal& a, const BlockTridiagonalFactor& f, int first_free,
                                const std::vector<ContactPoint>& contacts, ContactWorkspace& ws);

// Step 2: W for the contacts' current directions, then projected Gauss-Seidel; impulses in ws.impulse
// (3 per contact: n, t1, t2). `warm_start`: start from the normal impulses already in ws.impulse
// (the caller's guess, e.g. the previous sub-step's); otherwise from zero.
ContactSolveResult solve_contact_impulses(const std::vector<ContactPoint>& contacts, double dt, double mu,
                                          int iterations, bool warm_start, ContactWorkspace& ws);

// Step 3: the velocity change A^-1 H^T p of the impulses, into ws.h_t_p (6 per free node).
void contact_velocity_change(const BlockTridiagonal& a, const BlockTridiagonalFactor& f,
                             const std::vector<ContactPoint>& contacts, ContactWorkspace& ws);

// All three steps; adds the velocity correction to `dv` (6 per free node).
// `first_free`: global index of local node 0. Writes impulses per contact (3 each: n, t1, t2) into ws.impulse.
ContactSolveResult solve_contacts(const BlockTridiagonal& a, const BlockTridiagonalFactor& f, int first_free,
                                  const std::vector<ContactPoint>& contacts, double dt, double mu, int iterations,
                                  ContactWorkspace& ws, Eigen::Ref<Eigen::VectorXd> dv);

}  // namespace gw
