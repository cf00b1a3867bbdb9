#pragma once
// How rough the vessel wall is at the scale of a cross-section.
//
// A surface from a segmentation (marching cubes on 0.3-0.6 mm voxels, then smoothed) keeps a
// staircase of about half a voxel: for a 1.2 mm coronary the hits of a section stray by ~4% of
// the radius rms and up to ~20%, where a generated or CAD surface strays by 0.2%. The
// cross-section tests tuned on smooth walls (a round section's farthest / nearest hit < 1.12, no
// hit more than 8-10% of the radius off its circle) then fail almost everywhere, no clean tube is
// found near a junction, and junction centres are placed from the merged lumen (several radii
// off). The estimate lets those tests allow for the wall's own roughness.
#include <Eigen/Core>
#include <vector>

#include "centerline/vessel_wall.hpp"

namespace gw {

// Inputs: the skeleton's chains (points along each vessel, off-axis is fine), the wall, the point
// spacing (mm). Output: the median, over sections every `spacing` along the chains where all 24
// rays hit and the farthest / nearest hit is below 1.4, of the rms distance of the hits from
// their fitted circle divided by its radius; 0 when that median is below 1% (a smooth wall: every
// test then keeps its smooth-wall rule exactly) or fewer than 20 sections qualify.
double estimate_wall_noise(const std::vector<std::vector<Eigen::Vector3d>>& chains, const VesselWall& wall,
                           double spacing);

}  // namespace gw
