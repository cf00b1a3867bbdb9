#pragma once
// k-way junctions: a trifurcation comes out of the MCF skeleton as two junction nodes joined by a
// short chain. After re-centring (junction_centre.hpp) both sit where the vessel axes meet, less than
// a vessel radius apart; as separate bifurcations they would give the observation a wrong-branch
// geometry measured from the wrong place and a fork that does not exist.
#include <Eigen/Core>
#include <vector>

#include "centerline/refine_branch.hpp"
#include "centerline/skeleton_tree.hpp"

namespace gw {

// Inputs: `tree` (skeleton chains between key nodes), `recentred` (junction positions after
// recentre_junctions, indexed like tree.nodes), `refined` (branches, indexed like tree.chains),
// `factor`. Two junctions joined by a chain are one when their re-centred positions are closer than
// `factor` times the sum of the radii of their thinnest other arms (median over the arm's first 8 mm,
// next to the junction): the two side branches' openings then overlap on the vessel they leave. A
// trifurcation's two skeleton junctions are 0.6 of that apart; two forks one vessel diameter apart
// are more than 1.3 (anatomies/junctions). The closest such pair is contracted in `tree`: the two
// nodes become one at the middle of their skeleton positions, every chain that met either now ends
// there, the chain and the second node are removed (node indices above it shift down by one).
// Output: true when a chain was contracted (refine and re-centre again), false when none qualifies.
bool merge_close_junctions(SkeletonTree& tree, const std::vector<Eigen::Vector3d>& recentred,
                           const std::vector<RefinedBranch>& refined, double factor);

}  // namespace gw
