#include "anatomy_gen/tree_spec.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace gw {
namespace {

using nlohmann::json;

double number(const json& j, const std::string& what) {
  if (!j.is_number()) throw SpecError(what + " must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw SpecError(what + " must be finite");
  return v;
}

Eigen::Vector3d vec3(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw SpecError(what + " must be an array of 3 numbers");
  return {number(j[0], what), number(j[1], what), number(j[2], what)};
}

BranchSpec parse_branch(const json& j, int index) {
  const std::string where = "branches[" + std::to_string(index) + "]";
  if (!j.is_object()) throw SpecError(where + " must be an object");
  BranchSpec b;
  b.name = j.value("name", "branch" + std::to_string(index));
  if (j.contains("parent")) {
    if (!j["parent"].is_number_integer()) throw SpecError(where + ".parent must be a branch index");
    b.parent = j["parent"].get<int>();
  }
  if (index == 0 && b.parent != -1) throw SpecError(where + " is the root (inlet) branch and cannot have a parent");
  if (index > 0 && (b.parent < 0 || b.parent >= index))
    throw SpecError(where + " ('" + b.name + "'): parent must be the index of an earlier branch (0.." +
                    std::to_string(index - 1) + "), got " + std::to_string(b.parent));
  if (!j.contains("points") || !j["points"].is_array() || j["points"].size() < 2)
    throw SpecError(where + " ('" + b.name + "'): points must be an array of at least 2 [x,y,z] points");
  for (size_t i = 0; i < j["points"].size(); ++i)
    b.points.push_back(vec3(j["points"][i], where + ".points[" + std::to_string(i) + "]"));
  for (size_t i = 1; i < b.points.size(); ++i)
    if ((b.points[i] - b.points[i - 1]).norm() < 1e-6)
      throw SpecError(where + " ('" + b.name + "'): points " + std::to_string(i - 1) + " and " + std::to_string(i) +
                      " coincide");
  if (!j.contains("radius")) throw SpecError(where + " ('" + b.name + "'): radius is missing");
  const json& r = j["radius"];
  if (r.is_array()) {
    if (r.size() != b.points.size())
      throw SpecError(where + " ('" + b.name + "'): radius has " + std::to_string(r.size()) + " values for " +
                      std::to_string(b.points.size()) + " points");
    for (size_t i = 0; i < r.size(); ++i) b.radii.push_back(number(r[i], where + ".radius"));
  } else {
    b.radii.assign(b.points.size(), number(r, where + ".radius"));
  }
  for (double v : b.radii)
    if (v <= 0.0) throw SpecError(where + " ('" + b.name + "'): radius must be > 0 mm, got " + std::to_string(v));
  return b;
}

DeformationSpec parse_deformation(const json& j) {
  if (!j.is_object()) throw SpecError("deformation must be an object");
  DeformationSpec d;
  d.present = true;
  d.center = vec3(j.at("center"), "deformation.center");
  d.axis = vec3(j.at("axis"), "deformation.axis");
  if (d.axis.norm() < 1e-9) throw SpecError("deformation.axis must be non-zero");
  d.axis.normalize();
  d.radial_contraction = number(j.value("radial_contraction", json(0.0)), "deformation.radial_contraction");
  d.axial_shortening = number(j.value("axial_shortening", json(0.0)), "deformation.axial_shortening");
  d.twist_deg_per_cm = number(j.value("twist_deg_per_cm", json(0.0)), "deformation.twist_deg_per_cm");
  d.phase = number(j.value("phase", json(0.0)), "deformation.phase");
  if (d.phase < 0.0 || d.phase > 1.0) throw SpecError("deformation.phase must be in [0,1]");
  if (std::abs(d.radial_contraction) >= 0.5 || std::abs(d.axial_shortening) >= 0.5)
    throw SpecError("deformation contraction/shortening must be below 0.5 (50%)");
  return d;
}

}  // namespace

TreeSpec parse_tree_spec(const std::string& text) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw SpecError(std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw SpecError("a spec must be a JSON object");
  TreeSpec s;
  if (!j.contains("name") || !j["name"].is_string() || j["name"].get<std::string>().empty())
    throw SpecError("name must be a non-empty string");
  s.name = j["name"].get<std::string>();
  for (char c : s.name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      throw SpecError("name '" + s.name + "' may hold only letters, digits, '_' and '-' (it names files)");
  s.description = j.value("description", "");
  if (j.contains("units") && j["units"] != "mm") throw SpecError("units must be \"mm\"");
  if (j.contains("blend")) s.blend = number(j["blend"], "blend");
  if (s.blend < 0.0 || s.blend > 2.0) throw SpecError("blend must be in [0,2]");
  if (j.contains("edge_per_radius")) s.edge_per_radius = number(j["edge_per_radius"], "edge_per_radius");
  if (s.edge_per_radius < 0.05 || s.edge_per_radius > 1.0) throw SpecError("edge_per_radius must be in [0.05,1]");
  if (!j.contains("branches") || !j["branches"].is_array() || j["branches"].empty())
    throw SpecError("branches must be a non-empty array");
  const int n = static_cast<int>(j["branches"].size());
  for (int i = 0; i < n; ++i) s.branches.push_back(parse_branch(j["branches"][i], i));
  if (j.contains("deformation")) s.deformation = parse_deformation(j["deformation"]);
  return s;
}

TreeSpec read_tree_spec(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SpecError(path + ": cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    return parse_tree_spec(ss.str());
  } catch (const SpecError& e) {
    throw SpecError(path + ": " + e.what());
  }
}

std::string tree_spec_to_json(const TreeSpec& s) {
  auto v = [](const Eigen::Vector3d& p) { return json::array({p.x(), p.y(), p.z()}); };
  json j;
  j["name"] = s.name;
  j["description"] = s.description;
  j["units"] = "mm";
  j["blend"] = s.blend;
  j["edge_per_radius"] = s.edge_per_radius;
  json branches = json::array();
  for (const BranchSpec& b : s.branches) {
    json jb;
    jb["name"] = b.name;
    if (b.parent >= 0) jb["parent"] = b.parent;
    jb["points"] = json::array();
    for (const auto& p : b.points) jb["points"].push_back(v(p));
    bool constant = true;
    for (double r : b.radii) constant = constant && r == b.radii.front();
    jb["radius"] = constant ? json(b.radii.front()) : json(b.radii);
    branches.push_back(jb);
  }
  j["branches"] = branches;
  if (s.deformation.present) {
    const DeformationSpec& d = s.deformation;
    j["deformation"] = {{"center", v(d.center)},
                        {"axis", v(d.axis)},
                        {"radial_contraction", d.radial_contraction},
                        {"axial_shortening", d.axial_shortening},
                        {"twist_deg_per_cm", d.twist_deg_per_cm},
                        {"phase", d.phase}};
  }
  return j.dump(2) + "\n";
}

}  // namespace gw
