#pragma once
// An anatomy as the task sees it: the vessel wall (VesselScene) and its centerline graph.
// Loaded from the fixed layout anatomies/<set>/<name>/<name>.{stl,truth.json} listed in
// anatomies/index.json, from explicit paths, or built in memory from any CenterlineGraph.
#include <memory>
#include <string>
#include <vector>

#include "base/graph/centerline_graph.hpp"
#include "engine/scene/vessel_scene.hpp"
#include "engine/wire/wire_params.hpp"
#include "task/polyline.hpp"

namespace gw {

struct Anatomy {
  std::string name;
  std::string mesh_path;                       // empty when built in memory
  CenterlineGraph graph;
  std::vector<Polyline> branch_lines;          // branch_lines[b] = graph.branches[b].points
  std::shared_ptr<const VesselScene> scene;    // nullptr = free space (no wall)
  // The wire this anatomy is navigated with when its index entry names one (an arch pool's aortic wire);
  // nullptr = the run's wire (the apps' --wire). make_navigation_task builds one wire model per anatomy.
  std::shared_ptr<const WireParams> wire;
};

// Wraps a graph (and optionally a scene). Throws std::invalid_argument when the graph has no
// targets or a branch with fewer than two distinct points.
Anatomy make_anatomy(const std::string& name, const CenterlineGraph& graph, std::shared_ptr<const VesselScene> scene);

// Loads and validates the mesh (load_valid_mesh), builds its scene and reads the truth graph.
// Throws std::runtime_error "<file>: <problem>".
Anatomy load_anatomy(const std::string& name, const std::string& mesh_path, const std::string& truth_path);

struct AnatomySource {
  std::string name, mesh, truth;  // absolute or working-directory-relative paths
  std::string wire;               // the index entry's wire parameter JSON, "" = the run's wire
  double heart_rate_bpm = 0;      // the index entry's heart rate (> 0: beats with its own field; lib/runner applies it)
};

// Resolves `spec`, a comma-separated list whose items are each
//   - a set name of the index ("train", "test", "sensitivity"): every anatomy of that set,
//   - an anatomy name of the index ("t1_straight_y"),
//   - a mesh path (.stl/.obj/.ply; the truth is <stem>.truth.json beside it) or a .truth.json path,
//   - another index's path (any other .json, e.g. a pool from gw-anatomy-pool): every anatomy it lists.
// Index paths are relative to the repository root (the index's parent folder's parent).
// Throws std::runtime_error naming the item that matches nothing (and the index file).
std::vector<AnatomySource> resolve_anatomy_sources(const std::string& spec, const std::string& index_path);

// The wire an index entry names (load_wire_params), nullptr when it names none. Throws std::runtime_error naming
// the anatomy and the file when it cannot be loaded.
std::shared_ptr<const WireParams> load_source_wire(const AnatomySource& source);

// resolve_anatomy_sources + load_anatomy for each, with the wire an index entry names (load_wire_params;
// throws std::runtime_error naming the anatomy and the file when it cannot be loaded).
std::vector<Anatomy> load_anatomies(const std::string& spec, const std::string& index_path);

// anatomies/index.json of the source tree this library was built from,
// overridden by the environment variable GW_ANATOMY_INDEX when set.
std::string default_anatomy_index();

// The items of a comma list ("t1, t2,,t3"), trimmed, empty ones dropped: --anatomies, and the apps'
// other list flags (--rows, --controllers).
std::vector<std::string> split_commas(const std::string& spec);

}  // namespace gw
