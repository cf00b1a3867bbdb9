#pragma once
// A short vessel between two close junctions (closely spaced forks) is re-attached at both ends by
// recentre_junctions, each end's lead running to a fitting window that lies past the other junction;
// the two leads then overlap and the chain doubles back on itself (5.1 mm between two forks, 9.4 mm of
// chain). Such a link is replaced by the straight segment between the two centres.
#include <Eigen/Core>
#include <vector>

#include "centerline/refine_branch.hpp"
#include "centerline/skeleton_tree.hpp"

namespace gw {

// Inputs: `tree` (chains between key nodes), `branches` (refined, indexed like tree.chains, running from
// chain.a to chain.b, ends at the re-centred junctions), `spacing` (mm). Every chain between two
// junctions whose ends are closer than four times its largest radius and which doubles back (steps
// backwards along the direction from one end to the other, and is over 1.5 times as long as that
// chord) is resampled as the straight segment between its ends
// (radii taken from the old chain at the same fraction of its points; elongation: not a tube).
// Output: `branches` updated in place; returns how many chains were straightened.
int straighten_junction_links(const SkeletonTree& tree, std::vector<RefinedBranch>& branches, double spacing);

}  // namespace gw
