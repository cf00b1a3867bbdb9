#pragma once
// VTK XML PolyData (.vtp, ASCII) files for ParaView: an episode, the vessel mesh, a
// centerline path. Open them together in ParaView (File > Open, select all, Apply).
// All writers are atomic (temporary file + rename) and throw ReportError "<path>: ..."
// when the file cannot be written, std::invalid_argument "<path>: ..." for bad input.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "apps/report/trajectory.hpp"
#include "centerline/graph/centerline_graph.hpp"
#include "engine/mesh/triangle_mesh.hpp"

namespace gw {

// One file per episode, two polylines (cells):
//   cell 0: the tip trace, one point per recorded frame with a finite tip position
//           (frames of a diverged episode with NaN positions are skipped);
//   cell 1: the final wire shape (last entry of wire_shapes), if any.
// Point data: "time_s", "action" (0 where not finite), "agent_in_control" (0/1),
// "frame" (frame index); final-wire points carry the values of the frame the shape was
// recorded at. Cell data "kind": 0 = tip trace, 1 = final wire (Threshold on it in ParaView).
void write_trace_vtp(const EpisodeTrace& trace, const std::string& path);

// Every recorded wire shape of the episode, one polyline each, with cell data "shape"
// (index), "frame" (-1 when unknown) and "time_s" (-1 when unknown): Threshold on
// time_s in ParaView to scrub through the insertion. Throws std::invalid_argument if
// the trace has no wire shape.
void write_wire_shapes_vtp(const EpisodeTrace& trace, const std::string& path);

// The vessel surface as polygons (triangles). Throws std::invalid_argument for an empty
// mesh, a face index out of range or a non-finite vertex.
void write_mesh_vtp(const TriangleMesh& mesh, const std::string& path);

// One polyline (e.g. TargetPath::points) with point data "arc_length_mm" and, when
// `radius` is given (one value per point), "radius_mm" for ParaView's Tube filter.
void write_polyline_vtp(const std::vector<Eigen::Vector3d>& points, const std::string& path,
                        const std::vector<double>& radius = {});

// Every branch of a centerline graph as a polyline; cell data "branch" and "parent",
// point data "radius_mm".
void write_centerline_vtp(const CenterlineGraph& graph, const std::string& path);

}  // namespace gw
