#include "engine/wire/beam_element.hpp"

#include "engine/wire/so3.hpp"

namespace gw {

void eval_beam_element(const WireModel& model, int e, const Eigen::Vector3d& xa, const Eigen::Matrix3d& ra,
                       const Eigen::Vector3d& xb, const Eigen::Matrix3d& rb, BeamElementEval& out) {
  const double l = model.length[e];
  const double inv_l = 1.0 / l;
  const Vec3 phi = so3_log(ra.transpose() * rb);
  const Mat3 rm = ra * so3_exp(0.5 * phi);
  const Vec3 d = xb - xa;
  const Vec3 g = rm.transpose() * d;

  out.strain.head<3>() = (g - Vec3(model.chord[e], 0, 0)) * inv_l;
  out.strain.tail<3>() = (phi - model.rest_phi[e]) * inv_l;

  // d phi = Jr^-1(phi) Rb^T (dtheta_b - dtheta_a); the mid frame's right perturbation is
  // mu = Rm^T dtheta_a + 0.5 Jr(phi / 2) d phi.
  const Mat3 dphi = so3_right_jacobian_inv(phi) * rb.transpose();
  const Mat3 half = 0.5 * so3_right_jacobian(0.5 * phi) * dphi;
  const Mat3 gx = hat(g);
  const Mat3 rmt = rm.transpose() * inv_l;
  out.jac.block<3, 3>(0, 0) = -rmt;
  out.jac.block<3, 3>(0, 3).noalias() = gx * (rm.transpose() - half) * inv_l;
  out.jac.block<3, 3>(0, 6) = rmt;
  out.jac.block<3, 3>(0, 9).noalias() = gx * half * inv_l;
  out.jac.block<3, 3>(3, 0).setZero();
  out.jac.block<3, 3>(3, 3) = -dphi * inv_l;
  out.jac.block<3, 3>(3, 6).setZero();
  out.jac.block<3, 3>(3, 9) = dphi * inv_l;

  out.energy = 0.5 * l * out.strain.dot(model.stiffness[e].cwiseProduct(out.strain));
}

}  // namespace gw
