#pragma once
// From a rough skeleton chain to a centred, smooth, evenly sampled branch with radii.
#include <Eigen/Core>
#include <vector>

#include "centerline/vessel_wall.hpp"

namespace gw {

struct BranchRefinement {
  double spacing = 0.5;          // output point spacing (mm)
  int recentre_passes = 2;       // cross-section re-centring passes
  int smoothing_iterations = 4;  // Laplacian passes after re-centring
  int rays = 24;                 // rays per cross-section
  double wall_noise = 0.0;       // the wall's roughness (estimate_wall_noise.hpp): 0 = smooth
};

struct RefinedBranch {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> radii;
  std::vector<double> elongation;  // per point: CrossSection::elongation (inf: not a tube)
};

// `chain` runs from its first to its last point. Interior points are moved onto the
// centre of their cross-section wherever it is a clean tube (not near bifurcations or
// caps); on a chain between two junctions closer than the vessel's diameter (a wide vessel
// between two branch origins, as on an aortic arch) also where the wall around the openings is
// one circle far off the point (open_cross_section.hpp). A free end (a terminal: inlet or target) is then extended straight along the
// branch to the wall, since the skeleton stops about a radius short of an outlet; a
// bound end (a bifurcation centre) stays exactly where it is. Radii are the fitted
// cross-section radii, interpolated along the branch where the section is not a tube.
RefinedBranch refine_branch(const std::vector<Eigen::Vector3d>& chain, bool free_start, bool free_end,
                            const VesselWall& wall, const BranchRefinement& options = {});

}  // namespace gw
