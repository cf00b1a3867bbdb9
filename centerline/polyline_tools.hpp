#pragma once
// Small polyline operations used on every centerline branch.
#include <Eigen/Core>
#include <vector>

namespace gw {

// Laplacian smoothing with fixed end points (`iterations` passes of weights 1/4, 1/2, 1/4).
std::vector<Eigen::Vector3d> smooth_polyline(std::vector<Eigen::Vector3d> points, int iterations);

// Taubin lambda|mu smoothing with fixed end points: each iteration a shrinking Laplacian pass
// (lambda 0.5) then an inflating one (mu -0.53). Removes point-to-point noise like
// smooth_polyline but does not pull a curved axis towards its inside (plain Laplacian passes
// moved the re-centred axis of the S-curved t4 by ~1% of the radius).
std::vector<Eigen::Vector3d> taubin_smooth_polyline(std::vector<Eigen::Vector3d> points, int iterations);

// Points at equal arc-length steps close to `spacing` (at least the two end points),
// end points kept exactly.
std::vector<Eigen::Vector3d> resample_polyline(const std::vector<Eigen::Vector3d>& points, double spacing);

// Unit tangents (central differences, one-sided at the ends). Zero-length pieces reuse
// the neighbouring tangent.
std::vector<Eigen::Vector3d> polyline_tangents(const std::vector<Eigen::Vector3d>& points);

// Least-squares line through `points` (at least two): their mean and the principal direction,
// oriented from the first point towards the last.
void fit_line(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d& point, Eigen::Vector3d& direction);

// Linear interpolation of `values` (one per point) at arc length `s` from the first point.
double interpolate_along(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& values, double s);

}  // namespace gw
