#pragma once
// The pure step function (like mj_step): advances `state` by model.dt under `control`, in
// model.substeps integration sub-steps of model.h (one linearisation each); a sub-step in which the
// wire would move too far for its linearised contacts (a whipping tip) is halved, recursively. With
// adaptive stepping (params.max_free_substep_s) a sub-step after one that met no wall is up to
// model.free_span sub-steps long, and halved before it changes anything where it finds a contact.
// Stages, each timed: assemble (beam forces and tangent stiffness, Eq. 1), solve (block-tridiagonal
// free motion), detect (wall proximity at the predicted positions), constraints (contact impulses by
// projected Gauss-Seidel on W = H A^-1 H^T, Eq. 2), then integrate and check for divergence.
#include <string>
#include <vector>

#include "engine/contact/contact_force_error.hpp"
#include "engine/scene/vessel_scene.hpp"
#include "engine/wire/wire_state.hpp"

namespace gw {

struct Control {
  double push_mm_per_s = 0;     // proximal insertion speed (negative retracts)
  double rotate_rad_per_s = 0;  // proximal axial rotation rate (right-handed about the inlet direction)
};

struct StepTimings {
  double detect_s = 0, assemble_s = 0, solve_s = 0, constraints_s = 0;
};

// The sweep cap of the reference contact solve (WireModel::reference_contact_solve_every).
constexpr int kReferenceContactSweeps = 20000;

struct StepReport {
  bool ok = true;
  std::string problem;            // why ok == false: NaN, exploding energy, node outside the wall, ...
  int contacts = 0;               // active contact constraints (last sub-step)
  double max_penetration_mm = 0;  // deepest wire-surface penetration of the wall over the sub-steps
  int free_nodes = 0;             // nodes out of the introducer (unknowns of the solve)
  int contact_iterations = 0;     // projected Gauss-Seidel sweeps used (most in a sub-step)
  int contact_solves = 0;         // sub-steps (halved ones' attempts included) that solved for contact impulses
  int capped_contact_solves = 0;  // of those, the ones whose solve stopped at its sweep cap unconverged
  std::vector<ContactForceError> contact_checks;  // model.reference_contact_solve_every > 0: one per check
  double energy = 0;              // elastic + kinetic energy [mN mm = uJ]
  int split_substeps = 0;         // sub-steps halved because the wire moved too fast for one, or a long one
                                  // (adaptive stepping) met the wall (see step.cpp)
  int long_substeps = 0;          // sub-steps longer than model.h taken (adaptive stepping in free lumen)
  StepTimings timings;            // summed over the sub-steps
};

// Advances the state by one step. `scene` nullptr = free space. Never continues a diverged
// simulation: on NaN, energy above model.energy_limit, a speed above params.max_speed_mm_per_s or a
// node more than params.divergence_margin_mm outside the wall it returns ok = false with `problem`
// set, and marks the state (state.diverged) so later steps refuse until it is reset.
// Throws std::invalid_argument when the state does not belong to the model or the control is not finite.
StepReport step(const WireModel& model, const VesselScene* scene, const Control& control, WireState& state);

}  // namespace gw
