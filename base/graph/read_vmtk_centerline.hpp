#pragma once
// VMTK centerlines (vmtkcenterlines' .vtp) -> the project's CenterlineGraph.
// In:  a VTK XML PolyData file (any encoding vtkXMLPolyDataWriter writes, see vtp_polylines.hpp)
//      with point array "MaximumInscribedSphereRadius" and one polyline per inlet-to-outlet path.
//      The paths share their common trunk point by point up to where they part (vmtkcenterlines
//      backtraces every target to the same source through the same Voronoi vertices).
// Out: one tree: a line's points are the tree's while they lie within
//      kVmtkSharedTrunkFraction x the local radius of it; the first point past that (backed
//      up while the distance still shrinks, i.e. to where the paths begin to part) is a
//      bifurcation. Branches run from the inlet (the end all lines share; with one line, its
//      first point, which is where vmtkcenterlines puts the source), radii = the maximum
//      inscribed sphere radius, targets numbered by number_targets. Units as in the file (VMTK
//      keeps the surface's; the project expects mm).
//      A file that 3D Slicer tagged SPACE=LPS (field data) is turned to RAS (x, y negated), as
//      read_slicer_markups does with LPS markups (README, "On your own mesh").
// Bad file: std::runtime_error "<path>: <problem>".
#include <string>

#include "base/graph/centerline_graph.hpp"

namespace gw {

inline constexpr double kVmtkSharedTrunkFraction = 0.05;

CenterlineGraph read_vmtk_centerline(const std::string& path);

}  // namespace gw
