#pragma once
// The axis of a side branch inside the lumen it shares with its parent vessel.
//
// A shallow side branch (the coronary diagonals leave the LAD at ~25 deg) shares one merged
// lumen with its parent for several radii, so its cross-sections only become round tubes
// ~6 radii out, where the branch already curves away. A straight axis extrapolated back from
// there lands the bifurcation about a parent radius too far distal. Inside the merged lumen the
// part of the wall that lies outside the parent's tube is still the side branch's own wall: a
// circle of the branch's radius fitted to those wall hits gives its centre much closer to the
// junction, where the branch is still straight.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "centerline/extract/vessel_wall.hpp"

namespace gw {

struct SideBranchAxis {
  bool ok = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      // a point on the axis (mean of the centres)
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // unit, away from the junction
  std::vector<Eigen::Vector3d> centres;                 // recovered centres, nearest the junction first
};

// `point`, `direction`: the branch's axis fitted where it is a clean tube (direction away from
// the junction); `radius`: its radius there. `parent_distance(q)`: distance from q to the
// parent's axis; `parent_radius`: the parent's radius at the junction. Wall hits farther than
// parent_radius + 0.5 radius from the parent's axis (past the junction fillet) are fitted, at
// stations every `step` from `point` back towards the junction (at most `reach` radii, until
// four stations in a row give no clean arc or the station is on the parent's axis). `ok` when
// at least four stations, spanning at least 1.5 radii, give a clean arc.
SideBranchAxis trace_side_branch_axis(const VesselWall& wall, const Eigen::Vector3d& point,
                                      const Eigen::Vector3d& direction, double radius,
                                      const std::function<double(const Eigen::Vector3d&)>& parent_distance,
                                      double parent_radius, double step, double reach = 25.0);

}  // namespace gw
