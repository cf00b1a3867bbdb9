// cardiac_motion_from_spec (lib/runner/heart_motion.hpp).
// Inputs: an anatomy spec (anatomies/*/NAME/NAME.spec.json) with a "deformation" block, the point to hold
// still. Output: the generator's deformation field (anatomy_gen/deformation.hpp) as a
// CardiacMotion: activation s plays the generator's phase. Throws std::runtime_error "<spec>: <problem>".
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "lib/runner/heart_motion.hpp"
#include "base/util/read_json_file.hpp"

namespace gw {

CardiacMotion cardiac_motion_from_spec(const std::string& spec_path, const Eigen::Vector3d& fixed_point) {
  const nlohmann::json j = read_json_file(spec_path, "anatomy spec");
  if (!j.is_object() || !j.contains("deformation") || !j["deformation"].is_object())
    throw std::runtime_error(spec_path + ": no \"deformation\" block: the anatomy has no cardiac field of its own "
                             "(give a motion file, --motion FILE)");
  const nlohmann::json& d = j["deformation"];
  auto number = [&](const char* key) {
    if (!d.contains(key) || !d[key].is_number())
      throw std::runtime_error(spec_path + ": deformation \"" + std::string(key) + "\" must be a number");
    return d[key].get<double>();
  };
  auto vec3 = [&](const char* key) {
    if (!d.contains(key) || !d[key].is_array() || d[key].size() != 3)
      throw std::runtime_error(spec_path + ": deformation \"" + std::string(key) + "\" must be three numbers");
    return Eigen::Vector3d(d[key][0].get<double>(), d[key][1].get<double>(), d[key][2].get<double>());
  };
  if (number("phase") != 0.0)
    throw std::runtime_error(spec_path + ": the mesh is the field's phase " + d["phase"].dump() +
                             ", not its rest shape: playing the field over it would deform it twice");
  CardiacMotion m;
  m.axis_origin = vec3("center");
  m.axis_direction = vec3("axis");
  m.contraction_mm = number("radial_contraction");  // a fraction: of a 1 mm reference radius
  m.reference_radius_mm = 1.0;
  m.shortening_mm = number("axial_shortening");
  m.reference_length_mm = 1.0;
  m.twist_deg_per_cm = number("twist_deg_per_cm");
  m.has_fixed_point = true;
  m.fixed_point = fixed_point;
  return m;
}

}  // namespace gw
