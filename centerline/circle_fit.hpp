#pragma once
// Circles fitted to wall hits in a cross-section's plane (2D points around a centre).
// (fit_cross_section keeps its own copy of the Kasa fit: calling this one instead moves every
// centerline in its last bits, ~1e-13 mm, and with them the results table's chaotic episodes.)
#include <Eigen/Core>
#include <vector>

namespace gw {

// Kasa circle fit: least squares on x^2 + y^2 + D x + E y + F = 0 (fixed-size normal equations).
// Output: `centre` and `radius`; false (outputs unspecified) when the fit is degenerate.
bool kasa_circle_fit(const std::vector<Eigen::Vector2d>& hits, Eigen::Vector2d& centre, double& radius);

// Angle (rad) the hits span around `centre`: 2 pi minus the largest gap between consecutive angles.
double arc_span(const std::vector<Eigen::Vector2d>& hits, const Eigen::Vector2d& centre);

}  // namespace gw
