#pragma once
// Centripetal Catmull-Rom spline through control points: smooth (C1), passes through
// every point, and never overshoots into cusps or loops (alpha = 1/2, Yuksel et al. 2011).
#include <Eigen/Core>
#include <vector>

namespace gw {

// Point at spline parameter u in [0, n-1] (segment floor(u), local t = u - floor(u)).
// End segments use mirrored phantom points, so the end tangent follows the last chord.
Eigen::Vector3d catmull_rom_point(const std::vector<Eigen::Vector3d>& control, double u);

// Dense samples: parameters u (increasing, first 0, last n-1, every control point included)
// with consecutive points at most `spacing` mm apart.
std::vector<double> catmull_rom_parameters(const std::vector<Eigen::Vector3d>& control, double spacing);

}  // namespace gw
