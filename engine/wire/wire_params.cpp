#include "engine/wire/wire_params.hpp"
#include "base/util/read_json_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace gw {

WireParams default_wire_params() { return WireParams{}; }

namespace {
bool known_field(const std::string& k) {
  static const char* names[] = {"length_mm", "tip_length_mm", "tip_curvature_per_mm", "diameter_mm",
                                "young_modulus_kpa", "tip_young_modulus_kpa", "poisson_ratio",
                                "density_kg_per_mm3", "shear_coefficient", "damping_mass", "damping_stiffness",
                                "element_length_mm", "tip_element_length_mm", "fine_region_mm", "friction",
                                "contact_margin_mm", "divergence_margin_mm", "max_speed_mm_per_s",
                                "contact_iterations", "max_substep_s", "max_free_substep_s", "inlet_clearance_mm", "contact_slack_mm", "friction_torque",
                                "per_axis_rotational_inertia", "comment"};
  for (const char* n : names)
    if (k == n) return true;
  return false;
}
}  // namespace

void check_wire_params(const WireParams& p, const std::string& where) {
  auto positive = [&](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
      throw std::runtime_error(where + ": field '" + name + "' must be a positive finite number");
  };
  positive(p.length_mm, "length_mm");
  positive(p.tip_length_mm, "tip_length_mm");
  positive(p.diameter_mm, "diameter_mm");
  positive(p.young_modulus_kpa, "young_modulus_kpa");
  positive(p.tip_young_modulus_kpa, "tip_young_modulus_kpa");
  positive(p.density_kg_per_mm3, "density_kg_per_mm3");
  positive(p.shear_coefficient, "shear_coefficient");
  positive(p.element_length_mm, "element_length_mm");
  positive(p.tip_element_length_mm, "tip_element_length_mm");
  positive(p.contact_margin_mm, "contact_margin_mm");
  positive(p.divergence_margin_mm, "divergence_margin_mm");
  positive(p.max_speed_mm_per_s, "max_speed_mm_per_s");
  positive(p.max_substep_s, "max_substep_s");
  positive(p.contact_slack_mm, "contact_slack_mm");
  if (!(p.max_free_substep_s >= 0) || !std::isfinite(p.max_free_substep_s))
    throw std::runtime_error(where + ": field 'max_free_substep_s' must be >= 0 (0: off)");
  if (!(p.inlet_clearance_mm >= 0)) throw std::runtime_error(where + ": field 'inlet_clearance_mm' must be >= 0");
  if (p.contact_iterations < 1) throw std::runtime_error(where + ": field 'contact_iterations' must be >= 1");
  if (p.tip_length_mm >= p.length_mm) throw std::runtime_error(where + ": tip_length_mm must be < length_mm");
  if (!(p.poisson_ratio > -1 && p.poisson_ratio < 0.5))
    throw std::runtime_error(where + ": field 'poisson_ratio' must be in (-1, 0.5)");
  if (!(p.friction >= 0) || !(p.damping_mass >= 0) || !(p.damping_stiffness >= 0) || !(p.fine_region_mm >= 0) ||
      !std::isfinite(p.tip_curvature_per_mm))
    throw std::runtime_error(where + ": friction, damping and fine_region_mm must be >= 0");
}

WireParams load_wire_params(const std::string& json_path) {
  const nlohmann::json j = read_json_file(json_path, "wire parameter file");
  if (!j.is_object()) throw std::runtime_error(json_path + ": expected a JSON object");
  WireParams p;
  auto get = [&](const char* name, double& field) {
    if (!j.contains(name)) return;
    if (!j[name].is_number()) throw std::runtime_error(json_path + ": field '" + name + "' must be a number");
    field = j[name].get<double>();
  };
  get("length_mm", p.length_mm);
  get("tip_length_mm", p.tip_length_mm);
  get("tip_curvature_per_mm", p.tip_curvature_per_mm);
  get("diameter_mm", p.diameter_mm);
  get("young_modulus_kpa", p.young_modulus_kpa);
  get("tip_young_modulus_kpa", p.tip_young_modulus_kpa);
  get("poisson_ratio", p.poisson_ratio);
  get("density_kg_per_mm3", p.density_kg_per_mm3);
  get("shear_coefficient", p.shear_coefficient);
  get("damping_mass", p.damping_mass);
  get("damping_stiffness", p.damping_stiffness);
  get("element_length_mm", p.element_length_mm);
  get("tip_element_length_mm", p.tip_element_length_mm);
  get("fine_region_mm", p.fine_region_mm);
  get("friction", p.friction);
  get("contact_margin_mm", p.contact_margin_mm);
  get("divergence_margin_mm", p.divergence_margin_mm);
  get("max_speed_mm_per_s", p.max_speed_mm_per_s);
  get("max_substep_s", p.max_substep_s);
  get("max_free_substep_s", p.max_free_substep_s);
  get("inlet_clearance_mm", p.inlet_clearance_mm);
  get("contact_slack_mm", p.contact_slack_mm);
  if (j.contains("contact_iterations")) {
    if (!j["contact_iterations"].is_number_integer())
      throw std::runtime_error(json_path + ": field 'contact_iterations' must be an integer");
    p.contact_iterations = j["contact_iterations"].get<int>();
  }
  auto get_bool = [&](const char* name, bool& field) {
    if (!j.contains(name)) return;
    if (!j[name].is_boolean()) throw std::runtime_error(json_path + ": field '" + name + "' must be true or false");
    field = j[name].get<bool>();
  };
  get_bool("friction_torque", p.friction_torque);
  get_bool("per_axis_rotational_inertia", p.per_axis_rotational_inertia);
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known_field(it.key())) throw std::runtime_error(json_path + ": unknown field '" + it.key() + "'");
  check_wire_params(p, json_path);
  return p;
}

}  // namespace gw
