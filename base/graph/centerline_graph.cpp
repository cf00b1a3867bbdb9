#include "base/graph/centerline_graph.hpp"

#include "base/graph/read_slicer_markups.hpp"
#include "base/graph/read_vmtk_centerline.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace gw {
namespace {

using nlohmann::json;

json vec_json(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d json_vec(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error(what + " must be an array of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw std::runtime_error(what + " must be an array of 3 numbers");
    v[i] = j[i].get<double>();
  }
  return v;
}

json terminal_json(const Terminal& t) {
  return {{"id", t.id}, {"position", vec_json(t.position)}, {"branch", t.branch}, {"radius", t.radius}};
}

Terminal json_terminal(const json& j, const std::string& what) {
  Terminal t;
  t.id = j.value("id", 0);
  t.position = json_vec(j.at("position"), what + ".position");
  t.branch = j.value("branch", -1);
  t.radius = j.value("radius", 0.0);
  return t;
}

using TerminalIt = std::vector<Terminal>::iterator;

// Runs of [first, last) (already sorted by `key`) whose consecutive keys differ by at most
// `tolerance`: chained, so a run may span more than the tolerance end to end.
template <class Key>
std::vector<std::pair<TerminalIt, TerminalIt>> tie_groups(TerminalIt first, TerminalIt last, double tolerance, Key key) {
  std::vector<std::pair<TerminalIt, TerminalIt>> groups;
  for (TerminalIt begin = first; begin != last;) {
    TerminalIt end = begin + 1;
    while (end != last && key(*end) - key(*(end - 1)) <= tolerance) ++end;
    if (end - begin > 1) groups.emplace_back(begin, end);
    begin = end;
  }
  return groups;
}

// Orders tied targets by x, ends within kTargetCoordinateTieMm of each other by y, then by z.
void order_by_coordinates(TerminalIt first, TerminalIt last, int axis) {
  auto coordinate = [axis](const Terminal& t) { return t.position[axis]; };
  std::stable_sort(first, last, [&](const Terminal& a, const Terminal& b) { return coordinate(a) < coordinate(b); });
  if (axis == 2) return;
  for (auto& group : tie_groups(first, last, kTargetCoordinateTieMm, coordinate))
    order_by_coordinates(group.first, group.second, axis + 1);
}

// Distance along the tree from the inlet to the distal end of `branch`.
double path_length_to_end(const CenterlineGraph& g, int branch) {
  double length = 0.0;
  for (int b = branch; b >= 0; b = g.branches[b].parent) length += polyline_length(g.branches[b].points);
  return length;
}

}  // namespace

double polyline_length(const std::vector<Eigen::Vector3d>& points) {
  double length = 0.0;
  for (size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

void number_targets(CenterlineGraph& g) {
  std::vector<char> has_child(g.branches.size(), 0);
  for (const auto& b : g.branches)
    if (b.parent >= 0) has_child[b.parent] = 1;
  std::vector<Terminal> leaves;
  for (const auto& b : g.branches) {
    if (has_child[b.id] || b.points.empty()) continue;
    leaves.push_back({0, b.points.back(), b.id, b.radii.empty() ? 0.0 : b.radii.back()});
  }
  std::vector<double> length(g.branches.size());
  for (const auto& t : leaves) length[t.branch] = path_length_to_end(g, t.branch);
  auto path_length = [&](const Terminal& t) { return length[t.branch]; };
  // Exact order first, so that every later stage starts from the same sequence.
  std::sort(leaves.begin(), leaves.end(), [&](const Terminal& a, const Terminal& b) {
    return std::make_tuple(length[a.branch], a.position.x(), a.position.y(), a.position.z()) <
           std::make_tuple(length[b.branch], b.position.x(), b.position.y(), b.position.z());
  });
  for (auto& group : tie_groups(leaves.begin(), leaves.end(), kTargetLengthTieMm, path_length))
    order_by_coordinates(group.first, group.second, 0);
  for (size_t k = 0; k < leaves.size(); ++k) leaves[k].id = static_cast<int>(k + 1);
  g.targets = std::move(leaves);
}

TargetPath plan_path(const CenterlineGraph& g, int target_id) {
  const auto it = std::find_if(g.targets.begin(), g.targets.end(), [&](const Terminal& t) { return t.id == target_id; });
  if (it == g.targets.end()) {
    std::ostringstream s;
    s << "target " << target_id << " does not exist; valid targets are 1.." << g.targets.size();
    throw std::invalid_argument(s.str());
  }
  TargetPath path;
  path.target_id = target_id;
  for (int b = it->branch; b >= 0; b = g.branches.at(b).parent) path.branches.push_back(b);
  std::reverse(path.branches.begin(), path.branches.end());

  for (size_t i = 0; i < path.branches.size(); ++i) {
    const CenterlineBranch& branch = g.branches[path.branches[i]];
    // A child starts at its parent's bifurcation centre: skip the duplicated point.
    const size_t first = (i == 0 || branch.points.empty()) ? 0 : 1;
    for (size_t p = first; p < branch.points.size(); ++p) {
      path.points.push_back(branch.points[p]);
      path.radii.push_back(p < branch.radii.size() ? branch.radii[p] : 0.0);
    }
    if (i + 1 < path.branches.size()) {
      const int next = path.branches[i + 1];
      for (const Bifurcation& bif : g.bifurcations) {
        if (std::find(bif.children.begin(), bif.children.end(), next) == bif.children.end()) continue;
        PathBifurcation step{bif.id, next, {}};
        for (int c : bif.children)
          if (c != next) step.wrong_children.push_back(c);
        path.bifurcations.push_back(step);
        break;
      }
    }
  }
  path.length = polyline_length(path.points);
  return path;
}

std::string centerline_to_json(const CenterlineGraph& g, int indent) {
  json j;
  j["schema"] = "guidewire-nav/centerline/1";
  j["units"] = "mm";
  json inlet = terminal_json(g.inlet);
  inlet.erase("id");
  inlet["direction"] = vec_json(g.inlet_direction);
  j["inlet"] = inlet;
  j["targets"] = json::array();
  for (const auto& t : g.targets) j["targets"].push_back(terminal_json(t));
  j["branches"] = json::array();
  for (const auto& b : g.branches) {
    json pts = json::array();
    for (const auto& p : b.points) pts.push_back(vec_json(p));
    j["branches"].push_back({{"id", b.id}, {"parent", b.parent}, {"points", pts}, {"radii", b.radii}});
  }
  j["bifurcations"] = json::array();
  for (const auto& bif : g.bifurcations)
    j["bifurcations"].push_back(
        {{"id", bif.id}, {"position", vec_json(bif.position)}, {"parent", bif.parent}, {"children", bif.children}});
  return j.dump(indent);
}

CenterlineGraph centerline_from_json(const std::string& text, const std::string& origin) {
  json j;
  try {
    j = json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(origin + ": malformed centerline JSON (" + e.what() + ")");
  }
  if (j.is_object() && j.contains("markups") && !j.contains("schema"))  // a 3D Slicer .mrk.json
    return centerline_from_slicer_markups(j, origin);
  try {
    CenterlineGraph g;
    g.inlet = json_terminal(j.at("inlet"), "inlet");
    g.inlet.id = 0;
    if (j.at("inlet").contains("direction")) g.inlet_direction = json_vec(j["inlet"]["direction"], "inlet.direction");
    for (const auto& jb : j.at("branches")) {
      CenterlineBranch b;
      b.id = jb.at("id").get<int>();
      b.parent = jb.value("parent", -1);
      for (const auto& p : jb.at("points")) b.points.push_back(json_vec(p, "branch point"));
      b.radii = jb.at("radii").get<std::vector<double>>();
      if (b.radii.size() != b.points.size())
        throw std::runtime_error("branch " + std::to_string(b.id) + " has " + std::to_string(b.points.size()) +
                                 " points but " + std::to_string(b.radii.size()) + " radii");
      if (b.id != static_cast<int>(g.branches.size()))
        throw std::runtime_error("branch ids must be 0..N-1 in order");
      g.branches.push_back(std::move(b));
    }
    for (const auto& b : g.branches)
      if (b.parent < -1 || b.parent >= static_cast<int>(g.branches.size()) || b.parent == b.id)
        throw std::runtime_error("branch " + std::to_string(b.id) + " has an invalid parent");
    for (const auto& jb : j.at("bifurcations")) {
      Bifurcation bif;
      bif.id = jb.at("id").get<int>();
      bif.position = json_vec(jb.at("position"), "bifurcation position");
      bif.parent = jb.value("parent", -1);
      bif.children = jb.value("children", std::vector<int>{});
      g.bifurcations.push_back(std::move(bif));
    }
    for (const auto& jt : j.at("targets")) g.targets.push_back(json_terminal(jt, "target"));
    return g;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(origin + ": malformed centerline JSON (" + e.what() + ")");
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(origin + ": " + e.what());
  }
}

CenterlineGraph read_centerline(const std::string& path) {
  const auto ends_with = [&](const std::string& tail) {
    if (path.size() < tail.size()) return false;
    return std::equal(tail.rbegin(), tail.rend(), path.rbegin(),
                      [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
  };
  if (ends_with(".vtp")) return read_vmtk_centerline(path);
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open centerline file");
  std::stringstream s;
  s << in.rdbuf();
  return centerline_from_json(s.str(), path);
}

void write_centerline(const CenterlineGraph& g, const std::string& path) {
  // Write to a temporary file and rename, so a failure never leaves half a file.
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    out << centerline_to_json(g, 1) << "\n";
    if (!out) throw std::runtime_error(path + ": write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error(path + ": cannot rename temporary file");
}

}  // namespace gw
