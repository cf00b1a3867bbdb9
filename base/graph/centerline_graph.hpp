#pragma once
// The centerline graph of a vessel tree: what `centerline` outputs, what the anatomy
// generator writes as ground truth, and what the navigation task plans on.
// JSON schema "guidewire-nav/centerline/1" (units: millimetres):
// {
//   "schema": "guidewire-nav/centerline/1", "units": "mm",
//   "inlet":   {"position": [x,y,z], "direction": [dx,dy,dz], "radius": r, "branch": b},
//   "targets": [{"id": 1, "position": [x,y,z], "branch": b, "radius": r}, ...],
//   "branches": [{"id": b, "parent": p or -1, "points": [[x,y,z], ...], "radii": [r, ...]}, ...],
//   "bifurcations": [{"id": k, "position": [x,y,z], "parent": b, "children": [c1, c2, ...]}, ...]
// }
// Branches run distally (away from the inlet): a child's first point is its parent's
// bifurcation centre. "inlet.direction" points into the vessel.
// Targets are the distal ends of leaf branches, numbered 1..K by increasing path
// length from the inlet: a deterministic rule that depends only on the geometry, not on
// mesh tessellation. Path lengths within 0.5 mm of each other are a tie (chained: 100.0,
// 100.4 and 100.8 all tie), broken by the end's x, ends within 1 mm in x by y, then by z.
// Why a tolerance: mirror-symmetric trees tie exactly, and extraction moves a path length
// by up to ~0.1 mm against its truth (the sensitivity pattern's 119.34 / 119.36 mm swapped
// when compared exactly); target ends move by less than 0.05 mm, so their coordinates are
// a stable tie-break.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace gw {

struct CenterlineBranch {
  int id = 0;
  int parent = -1;                      // branch this one leaves from; -1 for the root
  std::vector<Eigen::Vector3d> points;  // distal order, resampled at a fixed spacing
  std::vector<double> radii;            // distance to the wall at each point
};

struct Bifurcation {
  int id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int parent = -1;            // incoming branch
  std::vector<int> children;  // outgoing branches
};

struct Terminal {
  int id = 0;  // target number (1..K); 0 for the inlet
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int branch = -1;
  double radius = 0.0;
};

struct CenterlineGraph {
  Terminal inlet;
  Eigen::Vector3d inlet_direction = Eigen::Vector3d::UnitZ();
  std::vector<CenterlineBranch> branches;  // branches[i].id == i
  std::vector<Bifurcation> bifurcations;
  std::vector<Terminal> targets;           // targets[k].id == k + 1
};

// One step of a path: the bifurcation reached and which child leads to the target.
struct PathBifurcation {
  int bifurcation = -1;
  int correct_child = -1;
  std::vector<int> wrong_children;
};

// The route from the inlet to one target, as the navigation task needs it.
struct TargetPath {
  int target_id = 0;
  std::vector<int> branches;                  // root ... leaf
  std::vector<PathBifurcation> bifurcations;  // in the order they are met
  std::vector<Eigen::Vector3d> points;        // concatenated polyline, inlet to target
  std::vector<double> radii;
  double length = 0.0;
};

// Path from the inlet to target `target_id`; throws std::invalid_argument naming the
// valid ids when it does not exist.
TargetPath plan_path(const CenterlineGraph& graph, int target_id);

// Length of a branch polyline.
double polyline_length(const std::vector<Eigen::Vector3d>& points);

// Assigns target ids 1..K by the rule above (leaf branch ends sorted by path length).
void number_targets(CenterlineGraph& graph);
inline constexpr double kTargetLengthTieMm = 0.5;
inline constexpr double kTargetCoordinateTieMm = 1.0;

// JSON I/O. read throws std::runtime_error "<path>: <problem>" on a malformed file.
// read_centerline is the one reader for every centerline file the project accepts:
//   *.vtp                 VMTK centerlines (read_vmtk_centerline.hpp), any VTK XML encoding;
//   JSON with "markups"   3D Slicer markups, *.mrk.json (read_slicer_markups.hpp; LPS -> RAS);
//   other JSON            this schema.
// centerline_from_json also takes a Slicer markups text.
std::string centerline_to_json(const CenterlineGraph& graph, int indent = -1);
CenterlineGraph centerline_from_json(const std::string& text, const std::string& origin = "<string>");
CenterlineGraph read_centerline(const std::string& path);
void write_centerline(const CenterlineGraph& graph, const std::string& path);

}  // namespace gw
