#pragma once
// The axis of a branch inside the lumen it shares with its neighbours at a junction.
//
// Near a junction the vessels' lumens merge, so cross-sections there are not round and the
// branches' axes are only measured where each is a clean tube again: ~6 radii out for a
// coronary diagonal leaving the LAD at ~25 deg, where it already curves away. A straight axis
// extrapolated back from there put the bifurcation about a parent radius too far distal, and
// straight or Hermite lead-ins miss the true axes by up to ~0.2 radius. Yet inside the merged
// lumen the part of the wall that lies outside every other branch's tube is still this
// branch's own wall: a circle fitted to those wall hits gives its centre close to the junction.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "centerline/vessel_wall.hpp"

namespace gw {

struct MergedLumenAxis {
  bool ok = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      // a point on the axis (mean of the fitted centres)
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // unit, away from the junction
  std::vector<Eigen::Vector3d> centres;                 // every recovered centre, nearest the junction
                                                        // first (the axis is fitted on the nearest 3.5 r)
  std::vector<double> radii;                            // per centre: the fitted radius (measured while the
                                                        // arc spans > 250 deg, carried on below that)
};

struct MergedLumenQuery {
  // True for a wall point that belongs to this branch's own wall (outside the other branches'
  // tubes and their fillets).
  std::function<bool(const Eigen::Vector3d&)> own_wall;
  // True once a station (a point on this branch's axis) has reached the junction.
  std::function<bool(const Eigen::Vector3d&)> at_junction;
};

// `point`, `direction`: the branch's axis fitted where it is a clean tube (direction away from
// the junction); `radius`: its radius there. Circles are fitted to the branch's own wall hits at
// stations every `step` from `point` back towards the junction (at most `reach` radii, until four
// stations in a row give no clean arc or `at_junction`). `ok` when at least four stations,
// spanning at least 1.5 radii, give a clean arc and the axis through them is within 17 deg of
// `direction`. An arc is clean when no hit strays more than 8% of the radius from its circle, plus
// 3 `wall_noise` on a noisy wall (estimate_wall_noise.hpp; 0: smooth).
MergedLumenAxis trace_merged_lumen_axis(const VesselWall& wall, const Eigen::Vector3d& point,
                                        const Eigen::Vector3d& direction, double radius,
                                        const MergedLumenQuery& query, double step, double reach = 25.0,
                                        double wall_noise = 0.0);

}  // namespace gw
