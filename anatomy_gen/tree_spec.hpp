#pragma once
// A vessel-tree spec: what an anatomy is made of before it is meshed.
// JSON format (millimetres; documented in anatomies/README.md):
// {
//   "name": "t1_straight_y", "description": "...", "units": "mm",
//   "blend": 0.5,              // optional: junction fillet width, fraction of the smaller radius
//   "edge_per_radius": 0.25,   // optional: target triangle edge / local radius
//   "branches": [
//     {"name": "access", "points": [[x,y,z], ...], "radius": 1.75},
//     {"name": "left", "parent": 0, "points": [[...], ...], "radius": [2.0, 1.8, 1.5]}
//   ],
//   "deformation": {"center": [..], "axis": [..], "radial_contraction": 0.1,
//                   "axial_shortening": 0.08, "twist_deg_per_cm": 3, "phase": 0}   // optional
// }
// Branch 0 is the root; its first point is the inlet. Every other branch names a parent
// listed before it, and its first point lies on the parent's centreline. "radius" is one
// number (constant) or one value per control point (linear in between).
#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

namespace gw {

// A spec problem the author must fix; message is the problem (callers prefix the file).
class SpecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct BranchSpec {
  std::string name;
  int parent = -1;                      // index into TreeSpec::branches; -1 for the root
  std::vector<Eigen::Vector3d> points;  // control points, interpolated by a Catmull-Rom spline
  std::vector<double> radii;            // one per control point
};

// A smooth cardiac-like displacement field (see deform_point in deformation.hpp).
struct DeformationSpec {
  bool present = false;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // heart centre
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   // long axis, base -> apex
  double radial_contraction = 0.0;  // fraction the distance to the axis shrinks at phase 1
  double axial_shortening = 0.0;    // fraction the height along the axis shrinks at phase 1
  double twist_deg_per_cm = 0.0;    // rotation about the axis per cm of height at phase 1
  double phase = 0.0;               // in [0,1]; 0 = rest shape, 1 = maximum amplitude
};

struct TreeSpec {
  std::string name;
  std::string description;
  double blend = 0.5;
  double edge_per_radius = 0.25;
  std::vector<BranchSpec> branches;
  DeformationSpec deformation;
};

// Parses and checks the format (types, counts, radius > 0, finite numbers, parents).
// Geometric checks (child on parent, self-intersection) are in build_tree_geometry.
// Throws SpecError naming the problem.
TreeSpec parse_tree_spec(const std::string& json_text);

// Reads a file; throws SpecError "<path>: <problem>".
TreeSpec read_tree_spec(const std::string& path);

// The spec as JSON text (2-space indent), e.g. to record a deformation phase.
std::string tree_spec_to_json(const TreeSpec& spec);

}  // namespace gw
