#pragma once
// The ground-truth centerline graph of a vessel tree, in the schema `centerline` outputs.
#include "base/graph/centerline_graph.hpp"
#include "anatomy_gen/tree_geometry.hpp"

namespace gw {

// Splits every spec branch at the points where children leave it, so each graph branch
// runs from one bifurcation (or the inlet) to the next (or to an outlet); a child's first
// point is its bifurcation centre, the point where it leaves the parent's centreline.
// Points are resampled at `spacing` mm (the exact ends kept); radii are the tube radii.
// Inlet = first point of the root, direction into the vessel; targets numbered by
// number_targets. Graph branch ids follow the spec order, then distal order.
CenterlineGraph build_truth_graph(const TreeGeometry& geometry, double spacing = 0.5);

}  // namespace gw
