#pragma once
// The vessel's cross-section through a point, in the plane normal to the centerline:
// rays cast in that plane hit the wall; a circle fitted to the hits gives the true
// centre (the skeleton sits off-axis) and the radius.
#include <Eigen/Core>
#include <limits>

#include "centerline/vessel_wall.hpp"

namespace gw {

struct CrossSection {
  bool tube = false;  // the hits look like one roughly circular lumen (false near
                      // bifurcations and caps, where the plane cuts more than a tube)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // fitted centre, in the plane
  double radius = 0.0;                               // fitted radius
  // Farthest / nearest hit seen from the fitted centre (+inf when a ray misses): 1 for
  // a round tube whatever the ray origin; clean junction-free sections stay close to 1.
  // On a noisy wall (wall_noise > 0) it is instead (r0 + a) / (r0 - a) of the oval fitted to the
  // hits' distances from that centre, r0 + a cos(2 phi - phi0) in least squares (the same figure
  // for an ellipse): a voxel staircase left after smoothing moves the nearest and farthest hits by
  // ~20% of a coronary radius, but it is made of higher angular harmonics and noise that the oval
  // leaves out, whereas two lumens merging at a junction are an oval.
  double elongation = std::numeric_limits<double>::infinity();
  // Rms distance of the hits from the fitted circle over its radius (+inf when no circle fits).
  double roughness = std::numeric_limits<double>::infinity();
};

// Casts `rays` rays from `p` in the plane normal to the unit `tangent`, up to
// `max_length` (about 3 radii), and fits a circle to the hits (Kasa fit). `tube` is
// false when a ray misses, the lumen is elongated (elongation >= 1.4), or the hits
// stray more than 10% of the radius from the circle.
// `wall_noise` (estimate_wall_noise.hpp; 0 for a smooth surface, which then gets exactly the
// rule above): the wall's own roughness, as an rms share of the radius. Above 0 the elongation is
// the oval's (above) and the hits may stray by 10% rms and by (10% + 4 wall_noise) at most.
CrossSection fit_cross_section(const VesselWall& wall, const Eigen::Vector3d& p, const Eigen::Vector3d& tangent,
                               double max_length, int rays = 24, double wall_noise = 0.0);

}  // namespace gw
