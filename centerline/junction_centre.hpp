#pragma once
// Bifurcation centres: the MCF junction node sits in the blended crotch, up to a couple
// of radii from where the vessel axes meet. Re-place it where the branches' straight
// continuations meet, and re-attach the branches there.
#include <Eigen/Core>
#include <vector>

#include "centerline/refine_branch.hpp"
#include "centerline/skeleton_tree.hpp"

namespace gw {

// For every junction of `tree` (3+ chains): fits a line to each incident branch over
// arc lengths [1.5, 3.5] local radii from the junction (refined points, clean tube
// sections), takes the least-squares nearest point to all lines as the new centre
// (kept only when the lines are not all parallel and it lies within `max_shift` radii
// of the old one, in units of the widest arm radius), then replaces the part of each branch before its fitting window by a straight run from
// the centre at `spacing`. `nodes` (junction positions, indexed like tree.nodes) and
// `branches` (indexed like tree.chains, running from chain.a to chain.b) are updated.
// A side branch off a vessel that goes on (the other two arms nearly opposite, or, where that
// vessel curves through the junction, the side arm clearly the thinnest) is traced back into the
// lumen it shares with that vessel (merged_lumen_axis.hpp) before its axis is intersected with the
// vessel's. `wall_noise` (estimate_wall_noise.hpp; 0 on a smooth surface) loosens the traced arcs'
// fit tolerance by the wall's own roughness.
// Per junction, in named stages (junction_centre.cpp): junction_arms, fit_arm_axes, least_squares_centre,
// side_branch_centre, trace_arms, reattach_arms.
void recentre_junctions(const SkeletonTree& tree, std::vector<Eigen::Vector3d>& nodes,
                        std::vector<RefinedBranch>& branches, const VesselWall& wall, double spacing,
                        double max_shift = 6.0, double wall_noise = 0.0);

}  // namespace gw
