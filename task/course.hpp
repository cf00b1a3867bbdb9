#pragma once
// The route to one target, prepared once per (anatomy, target) so that resetting an episode
// costs nothing: the path polyline, the geometry of every bifurcation met on the way, and
// the sequence of goals (one intermediate target per bifurcation, paper 2.2 / docs/architecture.md "Trees").
#include <Eigen/Core>
#include <vector>

#include "base/graph/centerline_graph.hpp"
#include "task/branch_lumen.hpp"
#include "task/polyline.hpp"
#include "task/task_config.hpp"

namespace gw {

struct CourseBifurcation {
  int bifurcation_id = -1;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double arc = 0.0;              // arc length of the centre along the course polyline
  int first_segment = 0;         // first course segment past the centre (the correct continuation)
  Eigen::Vector3d correct_direction = Eigen::Vector3d::UnitX();  // c: unit, centre -> correct child
  std::vector<int> wrong_branches;                 // graph branch ids of the wrong children
  Eigen::Vector3d approach_direction = Eigen::Vector3d::UnitX();  // p: unit, along the course into the centre
  Eigen::Vector3d omega_normal = Eigen::Vector3d::UnitX();  // normal of omega's plane: c or p (TaskConfig)
  std::vector<Eigen::Vector3d> wrong_in_plane;     // w_p: unit wrong directions in omega's plane: w (or w - c
                                                   // for OmegaPlane::kApproach) projected on it; zero when
                                                   // parallel to the normal; with JunctionModel::kCombined also those of
                                                   // the close bifurcations that follow (after this one's own)
  // TaskScale::kVessel only (empty / 0 otherwise):
  std::vector<BranchLumen> wrong_lumens;           // per wrong_branches entry: its radius and ostium
  double parent_radius = 0.0;                      // the course's median radius over the 8 mm before the centre
  double control_radius = 0.0;                     // the policy acts within this of the centre
};

struct Course {
  int target_id = 0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Polyline line;                                   // inlet -> target
  std::vector<CourseBifurcation> bifurcations;     // in the order they are met
  // Goals, in order: goal k < last belongs to bifurcation k and lies its control_radius past its
  // centre in the correct branch (where the policy hands control back); the last goal is the
  // target itself (so a single-bifurcation pattern has exactly one goal, as in the paper's training).
  std::vector<double> goal_arc;
  // Per goal, the arc lambda is measured to: goal_arc, or the intermediate target
  // TaskConfig::intermediate_target_mm past the bifurcation (the last one is the target).
  std::vector<double> lambda_arc;
  bool policy_always = true;                       // resolved ControlMode for this course
  bool vessel_scale = false;                       // resolved TaskScale: true = kVessel
};

// Builds the course to `target_id`. `branch_lines[b]` is make_polyline(graph.branches[b].points).
// Throws std::invalid_argument for an unknown target (plan_path's message) or a degenerate path.
Course make_course(const CenterlineGraph& graph, const std::vector<Polyline>& branch_lines, int target_id,
                   const TaskConfig& config);

}  // namespace gw
