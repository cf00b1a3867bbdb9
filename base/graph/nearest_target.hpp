#pragma once
// --target-point x,y,z: the target (numbered end) nearest a point, e.g. a 3D Slicer fiducial.
// In:  a graph with numbered targets; a point in the graph's frame (mm).
// Out: the id (1..K) of the target whose end is nearest the point.
// Throws std::invalid_argument, naming the distance and every target, when the graph has no
// target, when the inlet is nearer than every target, or when the nearest target's end is
// farther than max(kTargetPointRadii x its radius, kTargetPointMinMm): a point several radii
// from every end was not meant for one of them (a wrong frame, e.g. LPS against RAS, or a
// point along a vessel rather than at its end).
#include <Eigen/Core>

#include "base/graph/centerline_graph.hpp"

namespace gw {

inline constexpr double kTargetPointRadii = 3.0;
inline constexpr double kTargetPointMinMm = 2.0;

int nearest_target(const CenterlineGraph& graph, const Eigen::Vector3d& point);

}  // namespace gw
