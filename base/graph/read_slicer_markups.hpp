#pragma once
// 3D Slicer markups (.mrk.json, schema markups-schema-v1.0.x) -> the project's CenterlineGraph.
// In:  a markups file. Every markup of type "Curve", "ClosedCurve" or "Line" is a polyline through
//      its control points (points with positionStatus "undefined" are skipped; Slicer draws a
//      spline through them, so place them densely or export a resampled curve, as SlicerVMTK's
//      Extract Centerline does). Radii: the curve's "Radius" measurement (controlPointValues,
//      what Extract Centerline writes), else 0 (unknown; the navigation does not need them).
// Out: the first curve runs from the inlet (its first point). Every other curve leaves the tree
//      where its start lies within max(kSlicerJoinRadii x radius, kSlicerJoinMm) of a point of
//      a curve already placed (a curve whose end, not its start, is there is reversed): the
//      tree is split there, a bifurcation made, and the curve's first control point (the user's
//      click at the junction) replaced by that tree point. Curves are placed in file order as
//      soon as they can be; one that never touches the tree is an error naming it.
//      Targets: leaf ends, numbered by number_targets. Units: "mm" (default) or "um".
// Coordinates: the project works in RAS, Slicer's world frame. A markup in "LPS" (Slicer's
// default for files since 4.11; also assumed when coordinateSystem is missing) is converted to
// RAS by negating x and y. Slicer also writes its model files (STL/OBJ/PLY/VTK) in LPS by default
// since 4.11 and says so in the file header ("SPACE=LPS"): such a mesh must be turned to RAS the
// same way (declared_coordinate_space) for the curves to lie inside it.
// read_slicer_points returns the control points of every "Fiducial" (point list) markup, in RAS:
// target points for nearest_target (--target-point).
// Bad file: std::runtime_error "<path>: <problem>".
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/graph/centerline_graph.hpp"

namespace gw {

inline constexpr double kSlicerJoinRadii = 2.0;
inline constexpr double kSlicerJoinMm = 3.0;

struct SlicerPoint {
  std::string label;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // RAS, mm
};

CenterlineGraph centerline_from_slicer_markups(const nlohmann::json& markups, const std::string& origin);
CenterlineGraph read_slicer_markups(const std::string& path);
std::vector<SlicerPoint> read_slicer_points(const std::string& path);

}  // namespace gw
