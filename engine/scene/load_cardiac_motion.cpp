// load_cardiac_motion (engine/scene/wall_motion.hpp).
// Input: the path of a motion JSON file. Output: its CardiacMotion (missing keys keep their defaults;
// "fixed_point" missing or "inlet": hold_inlet).
// Throws std::runtime_error "<file>: <problem>".
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "engine/scene/wall_motion.hpp"
#include "base/util/read_json_file.hpp"

namespace gw {

CardiacMotion load_cardiac_motion(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "motion file");
  if (!j.is_object()) throw std::runtime_error(path + ": the motion file must hold a JSON object");
  static const std::set<std::string> known = {
      "heart_rate_bpm", "systole_fraction", "phase_offset",        "axis_origin",    "axis_direction",
      "contraction_mm", "reference_radius_mm", "shortening_mm",    "reference_length_mm", "twist_deg_per_cm",
      "rotation_deg",   "translation_mm",   "fixed_point", "comment",  "phase_surfaces"};
  for (const auto& item : j.items())
    if (!known.count(item.key())) throw std::runtime_error(path + ": unknown key \"" + item.key() + "\"");
  CardiacMotion m;
  auto number = [&](const char* key, double& v) {
    if (!j.contains(key)) return;
    if (!j[key].is_number()) throw std::runtime_error(path + ": \"" + key + "\" must be a number");
    v = j[key].get<double>();
  };
  auto vec3 = [&](const char* key, Eigen::Vector3d& v) {
    if (!j.contains(key)) return;
    const auto& a = j[key];
    if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() || !a[2].is_number())
      throw std::runtime_error(path + ": \"" + key + "\" must be an array of three numbers");
    v = Eigen::Vector3d(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
  };
  number("heart_rate_bpm", m.heart_rate_bpm);
  number("systole_fraction", m.systole_fraction);
  number("phase_offset", m.phase_offset);
  vec3("axis_origin", m.axis_origin);
  vec3("axis_direction", m.axis_direction);
  number("contraction_mm", m.contraction_mm);
  number("reference_radius_mm", m.reference_radius_mm);
  number("shortening_mm", m.shortening_mm);
  number("reference_length_mm", m.reference_length_mm);
  number("twist_deg_per_cm", m.twist_deg_per_cm);
  number("rotation_deg", m.rotation_deg);
  vec3("translation_mm", m.translation_mm);
  // The held point: a point, the anatomy's inlet (the default: a guide catheter engaged in the ostium
  // moves with it, so the wire's entry does not move against the vessel), or none (the introducer stays
  // in the room while the vessel moves away from it).
  const nlohmann::json held = j.contains("fixed_point") ? j["fixed_point"] : nlohmann::json("inlet");
  if (held.is_string() && held == "inlet") {
    m.hold_inlet = true;
  } else if (held.is_string() && held == "none") {
  } else if (held.is_array()) {
    vec3("fixed_point", m.fixed_point);
    m.has_fixed_point = true;
  } else {
    throw std::runtime_error(path + ": \"fixed_point\" must be an array of three numbers, \"inlet\" or \"none\"");
  }
  if (j.contains("phase_surfaces")) {
    const auto& list = j["phase_surfaces"];
    if (!list.is_array() || list.size() < 2)
      throw std::runtime_error(path + ": \"phase_surfaces\" must be an array of at least two surface files");
    for (const auto& item : j.items())
      if (item.key() != "phase_surfaces" && item.key() != "heart_rate_bpm" && item.key() != "phase_offset" &&
          item.key() != "comment" && item.key() != "fixed_point")
        throw std::runtime_error(path + ": \"" + item.key() + "\" is a parametric motion key: with \"phase_surfaces\" "
                                 "the wall follows the surfaces (keep only heart_rate_bpm, phase_offset, "
                                 "fixed_point)");
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    for (const auto& f : list) {
      if (!f.is_string()) throw std::runtime_error(path + ": \"phase_surfaces\" must hold file names");
      const std::filesystem::path p(f.get<std::string>());
      m.phase_surfaces.push_back(p.is_absolute() ? p.string() : (folder / p).string());
    }
  }
  return m;
}

}  // namespace gw
