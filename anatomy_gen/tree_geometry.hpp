#pragma once
// The sampled geometry of a vessel tree: every branch as a dense centreline with radii,
// children snapped onto their parents, and the end caps. Everything downstream (the
// implicit surface, the mesher, the ground-truth graph) reads this, never the raw spec.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "anatomy_gen/tree_spec.hpp"

namespace gw {

struct BranchCurve {
  std::string name;
  int parent = -1;                        // spec branch index; -1 for the root
  int parent_sample = -1;                 // sample of the parent where this branch starts
  std::vector<Eigen::Vector3d> points;    // dense samples, distal order
  std::vector<double> radii;              // tube radius at each sample
  std::vector<double> arclength;          // from the branch start
  std::vector<int> child_samples;         // own samples where children start (sorted, unique)
  bool cap_start = false;                 // root: flat inlet cap
  bool cap_end = false;                   // leaf: flat outlet cap
};

// A flat disc closing a tube end; normal points out of the vessel.
struct EndCap {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double radius = 0.0;
  int branch = -1;
  bool inlet = false;
};

struct TreeGeometry {
  std::vector<BranchCurve> branches;  // same order as the spec
  std::vector<EndCap> caps;           // inlet first, then outlets in branch order
  double blend = 0.5;
  double edge_per_radius = 0.25;
  double min_radius = 0.0, max_radius = 0.0;
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero(), bbox_max = Eigen::Vector3d::Zero();  // of the tubes
};

// Samples every branch (spacing `spacing` mm), snaps children onto their parents and
// checks the tree can be a vessel surface. Throws SpecError for: a child whose first point
// is not on its parent's centreline, a child starting at its parent's first point, a
// branch continued by a single child, a bend tighter than the tube radius, and branches
// (or one branch with itself) passing closer than the sum of their radii away from a junction.
TreeGeometry build_tree_geometry(const TreeSpec& spec, double spacing = 0.2);

// Spline parameter of the closest point of `parent`'s centreline to `p`, and its distance.
// Used to snap a child's first point, and to carry attachments through a deformation.
struct CurveLocation {
  double u = 0.0;
  double distance = 0.0;
};
CurveLocation locate_on_branch(const BranchSpec& parent, const Eigen::Vector3d& p, double spacing = 0.2);

}  // namespace gw
