#pragma once
// The vessel's cross-section through a point, in the plane normal to the centerline:
// rays cast in that plane hit the wall; a circle fitted to the hits gives the true
// centre (the skeleton sits off-axis) and the radius.
#include <Eigen/Core>
#include <limits>

#include "centerline/extract/vessel_wall.hpp"

namespace gw {

struct CrossSection {
  bool tube = false;  // the hits look like one roughly circular lumen (false near
                      // bifurcations and caps, where the plane cuts more than a tube)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // fitted centre, in the plane
  double radius = 0.0;                               // fitted radius
  // Farthest / nearest hit seen from the fitted centre (+inf when a ray misses): 1 for
  // a round tube whatever the ray origin; clean junction-free sections stay close to 1.
  double elongation = std::numeric_limits<double>::infinity();
};

// Casts `rays` rays from `p` in the plane normal to the unit `tangent`, up to
// `max_length` (about 3 radii), and fits a circle to the hits (Kasa fit). `tube` is
// false when a ray misses, the lumen is elongated (elongation >= 1.4), or the hits
// stray more than 10% of the radius from the circle.
CrossSection fit_cross_section(const VesselWall& wall, const Eigen::Vector3d& p, const Eigen::Vector3d& tangent,
                               double max_length, int rays = 24);

}  // namespace gw
