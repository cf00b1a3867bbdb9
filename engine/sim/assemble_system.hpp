#pragma once
// Stage "assemble": the linearised implicit Euler system of the free (inserted) nodes (paper Eq. 1),
//   (M (1 + dt alpha) + (dt beta + dt^2) K) dv = dt f - dt alpha M v - (dt beta + dt^2) K v - A_FH dv_H,
// with Rayleigh damping D = alpha M + beta K, K = -df/dx the beam tangent stiffness (Gauss-Newton part
// l J^T C J, symmetric positive semi-definite, plus each element's force resultant as a string, |n| / l
// (I - t t^T) on its ends' translations: see add_resultant_stiffness) and dv_H the change of the introducer's
// velocity.
// Unknowns: per free node (dv, domega), 6 DOF, nodes first_free..N-1 in order -> block tridiagonal.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "engine/solver/block_tridiagonal.hpp"
#include "engine/wire/beam_element.hpp"
#include "engine/wire/wire_state.hpp"

namespace gw {

struct DynamicsSystem {
  int first_free = 0;                 // global index of the first unknown node
  BlockTridiagonal a;
  Eigen::VectorXd rhs;                // 6 * a.size() (capacity may be larger)
  std::vector<Eigen::Matrix3d> rot;   // per node rotation matrices of the state
  std::vector<BeamElementEval> elem;  // per element evaluation (free elements only are filled)
  double elastic_energy = 0;          // of the free elements [mN mm]
};

// Builds the system for a sub-step of length `h` [s] (model.h, or a fraction of it when step() splits
// a violent sub-step) with the introducer moving at (push, rotate) from now on.
// Reuses `sys` storage: no allocation once sized for the model.
void assemble_system(const WireModel& model, const WireState& state, double push_mm_per_s, double rotate_rad_per_s,
                     double h, DynamicsSystem& sys);

// The same system as a general sparse matrix, assembled element by element from triplets (the
// cross-check path for SuiteSparse, and the route for structures that are not a chain); sub-step model.h.
void assemble_system_sparse(const WireModel& model, const WireState& state, double push_mm_per_s,
                            double rotate_rad_per_s, Eigen::SparseMatrix<double>& a, Eigen::VectorXd& rhs);

}  // namespace gw
