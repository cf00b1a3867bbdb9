#pragma once
// Material and geometry of a guidewire: one JSON-loadable parameter set.
// Units: millimetres, seconds, kilograms (so forces are mN and moduli kPa = mN/mm^2).
#include <string>

namespace gw {

struct WireParams {
  double length_mm = 310;              // paper 2.1.1
  double tip_length_mm = 6;            // curved distal tip (paper 2.1.1)
  double tip_curvature_per_mm = 0.2;   // rest curvature of the tip, in one plane (paper 2.1.1)
  // 0.014" = 0.3556 mm outer diameter (coronary workhorse wires, e.g. Abbott Hi-Torque BMW).
  double diameter_mm = 0.3556;
  // Nitinol austenite E ~ 40-75 GPa (Pelton et al., "Nitinol medical devices", 2000); 60 GPa in kPa.
  double young_modulus_kpa = 6.0e7;
  // Distal tapered core: the core is ground down to ~0.05-0.1 mm under the coil, so the *effective*
  // bending stiffness of the tip is ~1/10-1/50 of the body (Ritter et al. guidewire tip loads ~1 gf).
  double tip_young_modulus_kpa = 4.0e6;
  double poisson_ratio = 0.33;         // nitinol ~0.33
  double density_kg_per_mm3 = 6.45e-6; // nitinol 6450 kg/m^3
  double shear_coefficient = 0.9;      // Timoshenko k for a solid circular section (6(1+nu)/(7+6nu))
  double damping_mass = 1.0;           // Rayleigh alpha [1/s]
  double damping_stiffness = 1e-3;     // Rayleigh beta [s]
  double element_length_mm = 2.0;      // body element length
  double tip_element_length_mm = 0.5;  // finer elements in the distal `fine_region_mm`
  double fine_region_mm = 12.0;
  double friction = 0.1;               // Coulomb mu wire/vessel wall (PTFE/hydrophilic coated ~0.05-0.2)
  double contact_margin_mm = 0.1;      // detect contacts within this clearance (>> motion per 1 ms sub-step)
  double divergence_margin_mm = 0.5;   // a node further outside the wall than this = diverged
  double inlet_clearance_mm = 1.0;     // wire within this arc past the inlet is not tested (introducer mouth)
  double contact_slack_mm = 0.5;       // broad-phase cache: candidates gathered this much beyond reach
  // Integration sub-step: step() advances the model's control period dt in sub-steps no longer than
  // this. Contact of the stiff wire with curved walls (a tip wedged at a carina) chatters and
  // penetrates beyond ~1.5 ms per linearisation in the training Y and fails in the coronary tree at
  // 1 ms; 0.5 ms inserts through the coronary tree with < 0.01 mm penetration.
  double max_substep_s = 0.0005;
  // Adaptive stepping: in free lumen (the last sub-step met no wall) up to this long a sub-step, a
  // power-of-two multiple of the contact sub-step (rounded down, at most 16 of them); a long sub-step
  // whose swept contact test finds the wall is halved before it changes anything, down to max_substep_s,
  // so every contact is still solved at max_substep_s. 0 (the default): every sub-step max_substep_s.
  // The wire in an aorta-wide lumen is free in ~80% of its sub-steps, in a coronary tree in ~2%.
  double max_free_substep_s = 0;
  double max_speed_mm_per_s = 1e5;     // any node faster than 100 m/s = exploding simulation
  int contact_iterations = 100;        // projected Gauss-Seidel sweeps per sub-step (at most)
  // Friction with a lever arm: wall friction acts at the wire's surface (radius r from the axis), so its
  // tangential impulse also turns the wire (torque -r n x p_t on the rotational degrees of freedom) and
  // the wall can hold the wire's roll, winding up torsion that releases when it slips. Off (the paper's
  // model, the one the results table was measured with): friction acts at the axis, on translations only.
  bool friction_torque = false;
  // Rotational inertia per axis: rho J about the wire's tangent, rho I = rho J / 2 about the two bending
  // axes (the lumped node tensor turns with the node's frame, with the gyroscopic term w x (I w)). Off
  // (the table's model): the polar moment rho J about all three axes.
  bool per_axis_rotational_inertia = false;
};

// Reads a JSON object whose keys are the field names above; missing keys keep defaults.
// Throws std::runtime_error "<file>: <problem>" for unreadable files, wrong types, non-positive sizes.
WireParams load_wire_params(const std::string& json_path);

// A 0.014" coronary wire (values and sources in the struct comments).
WireParams default_wire_params();

// Throws std::runtime_error naming the first field out of range; `where` prefixes the message.
void check_wire_params(const WireParams& p, const std::string& where);

}  // namespace gw
