#pragma once
// A centerline polyline with arc length and smoothed unit tangents, and the two queries the task
// makes every step: project a point onto it, and read the point / tangent at an arc length.
#include <Eigen/Core>
#include <vector>

namespace gw {

struct Polyline {
  std::vector<Eigen::Vector3d> points;    // consecutive duplicates removed
  std::vector<double> arc;                // arc length at each point, arc[0] = 0
  std::vector<Eigen::Vector3d> tangents;  // unit tangent per point (central difference: smooth
                                          // across the kink where a child branch starts)
  double length = 0.0;
};

// Builds the arc-length table. Throws std::invalid_argument for fewer than two distinct points
// or a non-finite coordinate.
Polyline make_polyline(const std::vector<Eigen::Vector3d>& points);

struct PolylineProjection {
  double arc = 0.0;       // arc length of the closest point
  double distance = 0.0;  // distance from the query point to it
  int segment = 0;        // index of the segment holding it
};

// Closest point of segments [first_segment, last_segment] (-1 = up to the last segment) to `p`.
// Ties go to the proximal segment, so results are deterministic.
PolylineProjection project_onto_polyline(const Polyline& line, const Eigen::Vector3d& p, int first_segment = 0,
                                         int last_segment = -1);

// Point at arc length `arc` (clamped to [0, length]).
Eigen::Vector3d polyline_point(const Polyline& line, double arc);

// Unit tangent at arc length `arc` (clamped), interpolated between the point tangents.
Eigen::Vector3d polyline_tangent(const Polyline& line, double arc);

// Index of the segment containing arc length `arc` (clamped).
int polyline_segment_at(const Polyline& line, double arc);

}  // namespace gw
