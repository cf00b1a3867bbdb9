#include "task/anatomy.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "base/graph/anatomy_index.hpp"
#include "base/mesh/load_mesh.hpp"

namespace gw {

namespace fs = std::filesystem;

Anatomy make_anatomy(const std::string& name, const CenterlineGraph& graph, std::shared_ptr<const VesselScene> scene) {
  if (graph.targets.empty()) throw std::invalid_argument(name + ": centerline graph has no targets");
  Anatomy a;
  a.name = name;
  a.graph = graph;
  a.scene = std::move(scene);
  for (const CenterlineBranch& b : graph.branches) {
    try {
      a.branch_lines.push_back(make_polyline(b.points));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(name + ": branch " + std::to_string(b.id) + ": " + e.what());
    }
  }
  return a;
}

Anatomy load_anatomy(const std::string& name, const std::string& mesh_path, const std::string& truth_path) {
  const CenterlineGraph graph = read_centerline(truth_path);
  const TriangleMesh mesh = load_valid_mesh(mesh_path);
  auto scene = std::make_shared<const VesselScene>(make_vessel_scene(mesh));
  try {
    Anatomy a = make_anatomy(name, graph, std::move(scene));
    a.mesh_path = mesh_path;
    return a;
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(truth_path + ": " + e.what());
  }
}

std::vector<std::string> split_commas(const std::string& spec) {
  std::vector<std::string> items;
  std::string cur;
  for (char ch : spec + ",") {
    if (ch == ',') {
      const auto b = cur.find_first_not_of(" \t");
      if (b != std::string::npos) items.push_back(cur.substr(b, cur.find_last_not_of(" \t") - b + 1));
      cur.clear();
    } else {
      cur += ch;
    }
  }
  return items;
}

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::vector<AnatomySource> resolve_anatomy_sources(const std::string& spec, const std::string& index_path) {
  const std::vector<std::string> items = split_commas(spec);
  if (items.empty()) throw std::runtime_error("anatomy list is empty");
  std::vector<AnatomyEntry> index;
  bool index_read = false;
  std::vector<AnatomySource> out;
  for (const std::string& item : items) {
    const bool is_truth = ends_with(item, ".truth.json");
    const bool is_mesh = ends_with(item, ".stl") || ends_with(item, ".obj") || ends_with(item, ".ply") ||
                         ends_with(item, ".STL") || ends_with(item, ".OBJ") || ends_with(item, ".PLY");
    if (is_truth || is_mesh) {
      const fs::path p(item);
      std::string stem = p.filename().string();
      stem = is_truth ? stem.substr(0, stem.size() - 11) : p.stem().string();
      const fs::path truth = is_truth ? p : p.parent_path() / (stem + ".truth.json");
      const fs::path mesh = is_mesh ? p : p.parent_path() / (stem + ".stl");
      if (!fs::exists(mesh)) throw std::runtime_error(mesh.string() + ": mesh file does not exist");
      if (!fs::exists(truth))
        throw std::runtime_error(truth.string() + ": centerline truth file does not exist (needed beside " +
                                 mesh.string() + ")");
      out.push_back({stem, mesh.string(), truth.string(), "", 0.0});
      continue;
    }
    if (ends_with(item, ".json")) {  // another anatomy index (a generated pool): every anatomy it lists
      if (!fs::exists(item)) throw std::runtime_error(item + ": anatomy index does not exist");
      for (const AnatomyEntry& e : read_anatomy_index(item))
        out.push_back({e.name, e.mesh, e.truth, e.wire, e.heart_rate_bpm});
      continue;
    }
    if (!index_read) {
      index = read_anatomy_index(index_path);
      index_read = true;
    }
    bool found = false;
    for (const AnatomyEntry& e : index) {
      if (e.set == item || e.name == item) {
        out.push_back({e.name, e.mesh, e.truth, e.wire, e.heart_rate_bpm});
        found = true;
      }
    }
    if (!found)
      throw std::runtime_error("anatomy '" + item + "' is neither a set nor a name in " + index_path +
                               " nor a mesh/.truth.json path");
  }
  return out;
}

std::shared_ptr<const WireParams> load_source_wire(const AnatomySource& source) {
  if (source.wire.empty()) return nullptr;
  try {
    return std::make_shared<const WireParams>(load_wire_params(source.wire));
  } catch (const std::exception& e) {
    throw std::runtime_error("anatomy '" + source.name + "': its wire " + source.wire + ": " + e.what());
  }
}

std::vector<Anatomy> load_anatomies(const std::string& spec, const std::string& index_path) {
  std::vector<Anatomy> out;
  for (const AnatomySource& s : resolve_anatomy_sources(spec, index_path)) {
    out.push_back(load_anatomy(s.name, s.mesh, s.truth));
    out.back().wire = load_source_wire(s);
  }
  return out;
}

std::string default_anatomy_index() {
  if (const char* env = std::getenv("GW_ANATOMY_INDEX"); env && *env) return env;
  // The source tree this library was built from (task/CMakeLists.txt defines it).
  return (fs::path(GW_SOURCE_DIR) / "anatomies" / "index.json").string();
}

}  // namespace gw
