#pragma once
// The constant part of the simulation (like mjModel): discretised wire geometry and element stiffness.
// Nodes are numbered proximal (0) -> distal (N-1); element e joins nodes e and e+1. Node 0 is always
// held by the introducer (the proximal driver).
#include <Eigen/Core>
#include <vector>

#include "engine/wire/wire_params.hpp"

namespace gw {

using Vec6 = Eigen::Matrix<double, 6, 1>;

struct WireModel {
  WireParams params;
  double dt = 0.01;                        // control period: one step() call advances this much [s]
  int substeps = 1;                        // integration sub-steps per step() (params.max_substep_s)
  double h = 0.01;                         // integration sub-step dt / substeps [s]
  // Adaptive stepping (params.max_free_substep_s): in free lumen up to this many sub-steps of h are taken
  // as one; a power of two, 1 = off.
  int free_span = 1;
  int nodes = 0;
  double radius_mm = 0;                    // wire radius (contact thickness)
  std::vector<double> arc_from_tip;        // per node: arc length to the distal tip [mm]
  std::vector<double> mass;                // per node: lumped translational mass [kg]
  std::vector<double> rot_inertia;         // per node: lumped isotropic rotational inertia [kg mm^2]
  std::vector<double> length;              // per element: arc length at rest [mm]
  std::vector<double> chord;               // per element: chord length at rest [mm]
  std::vector<Eigen::Vector3d> rest_phi;   // per element: rest rotation vector from frame e to e+1 (local)
  std::vector<Vec6> stiffness;             // per element: (EA, kGA, kGA, GJ, EI, EI) [mN, mN mm^2]
  double energy_limit = 0;                 // elastic + kinetic energy above this = exploding [mN mm]
  // Diagnostic (bench-mechanics --contact-accuracy): every k-th sub-step (0 = never) the contact problem is
  // also solved to convergence on a copy, and how far the capped solve's forces are from it goes into the
  // StepReport (contact_checks). The trajectory is the same bit for bit, only slower.
  int reference_contact_solve_every = 0;
  int elements() const { return nodes - 1; }
};

// Discretises `params`: element length params.element_length_mm, refined to tip_element_length_mm over
// the distal fine_region_mm; tip elements (midpoint within tip_length_mm of the tip) get the rest
// rotation exp(kappa * l * z) (the tip bends towards local +y) and the tip modulus.
// Throws std::runtime_error for invalid params or dt <= 0.
WireModel make_wire_model(const WireParams& params, double dt = 0.01);

}  // namespace gw
