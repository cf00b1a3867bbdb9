#pragma once
// A vessel's lumen along a centreline, as TaskScale::kVessel reads it (task_config.hpp): the radius at
// each arc length, and for a wrong child where its centreline leaves the parent's lumen (its ostium).
#include <Eigen/Core>
#include <vector>

#include "task/polyline.hpp"

namespace gw {

struct RadiusProfile {
  std::vector<double> arc;     // arc length along the centreline, per point (non-decreasing)
  std::vector<double> radius;  // the vessel radius there (the distance from the centreline to the wall)
};

struct BranchLumen {
  RadiusProfile profile;       // along the child's centreline, arc as in make_polyline(child points)
  double ostium_arc = 0.0;     // first arc where the child's centreline is outside the parent's lumen
};

// Inputs: centreline points and the radius at each (same length, >= 1 point).
// Output: the profile; arc = cumulative point distances, so equal to make_polyline's arc at every point it
// keeps (it drops consecutive duplicates, which add no length). Throws std::invalid_argument on a length mismatch.
RadiusProfile make_radius_profile(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& radii);

// Radius at arc length `arc`, linear between points, clamped to the ends.
double radius_at(const RadiusProfile& profile, double arc);

// Inputs: a wrong child's centreline points and radii, the course polyline and its radius profile.
// Output: the child's profile, and its ostium: the arc where the child's centreline first gets farther from
// the course than the course's radius at the closest point (linear between the points around the crossing;
// the child's length if it never does).
BranchLumen make_branch_lumen(const std::vector<Eigen::Vector3d>& child_points, const std::vector<double>& child_radii,
                              const Polyline& course, const RadiusProfile& course_radius);

// Inputs: a profile and an arc interval. Output: the median radius over [from, to] sampled every 1 mm
// (a junction's bulge is a point or two of it), the radius at `to` for an empty interval.
double median_radius(const RadiusProfile& profile, double from, double to);

}  // namespace gw
