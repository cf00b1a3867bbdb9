#pragma once
// Shared helpers for the mechanics tests: small uniform beams and settling to rest.
#include <Eigen/Core>
#include <cmath>
#include <fstream>
#include <string>

#include "engine/sim/step.hpp"
#include "engine/wire/wire_model.hpp"
#include "engine/wire/wire_state.hpp"

namespace gw::test {

// Writes `text` to GW_BINARY_DIR/`name` (a wire parameter file for a test); returns its path.
inline std::string write_test_file(const std::string& name, const std::string& text) {
  const std::string path = std::string(GW_BINARY_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// A uniform straight beam (no curved tip, body modulus everywhere) of `length_mm` with elements of
// `element_mm`; the wire's own diameter and moduli unless overridden afterwards.
inline WireParams uniform_beam_params(double length_mm, double element_mm) {
  WireParams p = default_wire_params();
  p.length_mm = length_mm;
  p.tip_length_mm = element_mm;
  p.tip_curvature_per_mm = 0;
  p.tip_young_modulus_kpa = p.young_modulus_kpa;
  p.fine_region_mm = 0;
  p.element_length_mm = element_mm;
  return p;
}

// Steps with a zero control until every free node is slower than `tol` mm/s (or `max_steps`).
// Returns the steps taken; REQUIREs nothing so callers can check the report themselves.
inline int settle(const WireModel& model, WireState& state, int max_steps, double tol = 1e-7,
                  const VesselScene* scene = nullptr) {
  for (int s = 1; s <= max_steps; ++s) {
    const StepReport rep = step(model, scene, Control{}, state);
    if (!rep.ok) return -s;
    double vmax = 0;
    for (int i = 0; i < model.nodes; ++i) vmax = std::max(vmax, state.v[i].norm() + state.w[i].norm());
    if (vmax < tol) return s;
  }
  return max_steps;
}

}  // namespace gw::test
