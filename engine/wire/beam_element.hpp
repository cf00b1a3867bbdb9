#pragma once
// One geometrically exact Timoshenko (Cosserat) beam element between nodes a and b.
// Strains: shear/stretch Gamma = (Rm^T (xb - xa) - chord e1) / l in the mid frame Rm = Ra Exp(phi / 2),
// bending/twist Omega = (phi - phi0) / l with phi = Log(Ra^T Rb). Energy 0.5 l eps^T C eps with
// C = diag(EA, kGA, kGA, GJ, EI, EI). Shear uses the mid frame (one-point reduced integration), which
// keeps the element free of shear locking: nodal rotations of a cantilever are exact and the
// deflection error is l^2 / (4 L^2) relative.
#include <Eigen/Core>

#include "engine/wire/wire_model.hpp"

namespace gw {

using Mat6x12 = Eigen::Matrix<double, 6, 12>;
using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;

struct BeamElementEval {
  Vec6 strain;   // (Gamma, Omega)
  Mat6x12 jac;   // d strain / d (xa, theta_a, xb, theta_b), rotations as world-frame perturbations
  double energy = 0;
};

// Strains, their Jacobian and the elastic energy of element `e` at positions xa, xb and frames ra, rb.
void eval_beam_element(const WireModel& model, int e, const Eigen::Vector3d& xa, const Eigen::Matrix3d& ra,
                       const Eigen::Vector3d& xb, const Eigen::Matrix3d& rb, BeamElementEval& out);

}  // namespace gw
