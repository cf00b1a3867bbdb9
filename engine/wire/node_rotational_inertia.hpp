#pragma once
// The lumped rotational inertia tensor of node i in the world frame [kg mm^2].
// Inputs: the model; node i; its frame rotation r (columns: local axes, local x = the wire's tangent).
// Output: with params.per_axis_rotational_inertia, R diag(J, J/2, J/2) R^T = (J/2)(Id + t t^T), J =
// model.rot_inertia[i] (rho times the polar moment, lumped) and t the tangent: the polar moment about
// the axis, the bending moment rho I = rho J / 2 about the two others. Otherwise (the paper's model)
// J Id: the polar moment about all three axes.
#include <Eigen/Core>

#include "engine/wire/wire_model.hpp"

namespace gw {

Eigen::Matrix3d node_rotational_inertia(const WireModel& model, int i, const Eigen::Matrix3d& r);

}  // namespace gw
