#include "engine/wire/wire_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gw {

WireModel make_wire_model(const WireParams& p, double dt) {
  check_wire_params(p, "wire parameters");
  if (!(dt > 0) || !std::isfinite(dt)) throw std::runtime_error("make_wire_model: dt must be positive and finite");
  WireModel m;
  m.params = p;
  m.dt = dt;
  m.substeps = std::max(1, static_cast<int>(std::ceil(dt / p.max_substep_s - 1e-9)));
  m.h = dt / m.substeps;
  while (m.free_span < 16 && 2.0 * m.free_span * m.h <= p.max_free_substep_s * (1 + 1e-9)) m.free_span *= 2;
  m.radius_mm = 0.5 * p.diameter_mm;

  // Arc positions measured from the tip: fine spacing over the distal region, then body spacing,
  // each region split into equal elements so the last node lands exactly on the proximal end.
  std::vector<double> s{0.0};
  const double fine = std::min(p.fine_region_mm, p.length_mm);
  const int n_fine = fine > 0 ? std::max(1, static_cast<int>(std::ceil(fine / p.tip_element_length_mm - 1e-9))) : 0;
  for (int i = 1; i <= n_fine; ++i) s.push_back(fine * i / n_fine);
  const double rest = p.length_mm - fine;
  if (rest > 1e-9) {
    const int n_body = std::max(1, static_cast<int>(std::ceil(rest / p.element_length_mm - 1e-9)));
    for (int i = 1; i <= n_body; ++i) s.push_back(fine + rest * i / n_body);
  }
  std::reverse(s.begin(), s.end());  // proximal first
  m.nodes = static_cast<int>(s.size());
  m.arc_from_tip = s;

  const double r = m.radius_mm;
  const double area = M_PI * r * r;
  const double inertia = M_PI * r * r * r * r / 4.0;  // second moment of area of a solid circle
  m.mass.assign(m.nodes, 0.0);
  m.rot_inertia.assign(m.nodes, 0.0);
  double max_ei = 0;
  for (int e = 0; e + 1 < m.nodes; ++e) {
    const double l = s[e] - s[e + 1];
    const double mid = 0.5 * (s[e] + s[e + 1]);
    const bool tip = mid < p.tip_length_mm;
    const double E = tip ? p.tip_young_modulus_kpa : p.young_modulus_kpa;
    const double G = E / (2.0 * (1.0 + p.poisson_ratio));
    const double kappa = tip ? p.tip_curvature_per_mm : 0.0;
    m.length.push_back(l);
    // A circular arc of length l has chord 2 sin(k l / 2) / k, parallel to the frame rotated by k l / 2.
    m.chord.push_back(std::abs(kappa) > 1e-12 ? 2.0 * std::sin(0.5 * kappa * l) / kappa : l);
    m.rest_phi.emplace_back(0.0, 0.0, kappa * l);
    Vec6 k;
    k << E * area, p.shear_coefficient * G * area, p.shear_coefficient * G * area, G * 2.0 * inertia, E * inertia,
        E * inertia;
    m.stiffness.push_back(k);
    max_ei = std::max(max_ei, E * inertia);
    const double me = p.density_kg_per_mm3 * area * l;
    const double je = p.density_kg_per_mm3 * 2.0 * inertia * l;  // polar moment, used isotropically
    m.mass[e] += 0.5 * me;
    m.mass[e + 1] += 0.5 * me;
    m.rot_inertia[e] += 0.5 * je;
    m.rot_inertia[e + 1] += 0.5 * je;
  }
  // Bending the whole wire to a 0.1 mm radius (far beyond anything a vessel allows) stores
  // L * EI / (2 * 0.01 mm^2); more than that can only come from a blown-up simulation.
  m.energy_limit = p.length_mm * max_ei / (2.0 * 0.01);
  return m;
}

}  // namespace gw
