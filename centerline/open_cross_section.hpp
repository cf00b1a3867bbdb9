#pragma once
// The cross-section of a vessel where another branch opens out of its wall: the wall around
// the opening is still one circle, which a plain circle fit (cross_section.hpp) refuses because
// the rays through the opening run on into the other branch.
#include <Eigen/Core>

#include "centerline/cross_section.hpp"
#include "centerline/vessel_wall.hpp"

namespace gw {

// Casts 72 rays from `p` in the plane normal to the unit `tangent`, up to `max_length`; fits a
// circle to the hits, then repeatedly drops the hits that lie more than 15% of the radius
// outside it (the opening: those rays ran on into the other branch; misses are dropped too)
// and fits again. Output: `tube` true when the kept hits span at least 240 degrees around the
// centre, are at least half of the rays, and stray at most 8% of the radius from the circle;
// then `centre` (in the plane) and `radius` are the circle's and `elongation` is +inf (the
// section is not a clean tube: junction re-centring must not fit lines through it).
// Otherwise `tube` is false, `centre` = p and `radius` = the wall distance.
CrossSection fit_open_cross_section(const VesselWall& wall, const Eigen::Vector3d& p, const Eigen::Vector3d& tangent,
                                    double max_length);

}  // namespace gw
