#pragma once
// VTK XML PolyData (.vtp, zlib-compressed binary: vtp_document.hpp) files for ParaView: an episode,
// its time series (.pvd), the vessel mesh, a centerline path. Open them together in ParaView
// (File > Open, select all, Apply).
// All writers are atomic (temporary file + rename) and throw ReportError "<path>: ..."
// when the file cannot be written, std::invalid_argument "<path>: ..." for bad input.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "lib/report/trajectory.hpp"
#include "base/graph/centerline_graph.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

// One file per episode, two polylines (cells):
//   cell 0: the tip trace, one point per recorded frame with a finite tip position
//           (frames of a diverged episode with NaN positions are skipped);
//   cell 1: the final wire shape (last entry of wire_shapes), if any.
// Point data: "time_s", "action" (0 where not finite), "agent_in_control" (0/1),
// "frame" (frame index); final-wire points carry the values of the frame the shape was
// recorded at. Cell data "kind": 0 = tip trace, 1 = final wire (Threshold on it in ParaView).
void write_trace_vtp(const EpisodeTrace& trace, const std::string& path);

// One recorded wire shape (wire_shapes[shape]) and the tip's way up to it, two polylines:
//   cell 0: the tip trace from frame 0 to the shape's frame (finite positions only; may be empty),
//   cell 1: the wire shape, proximal to distal.
// Cell data "kind" (0 = tip trace, 1 = wire, as in write_trace_vtp); point data "arc_length_mm"
// along each polyline. Field-like cell data "frame" and "time_s" give the shape's frame and time
// (-1 when the trace does not record wire_shape_frame). Throws std::invalid_argument for a shape
// index out of range.
void write_wire_shape_vtp(const EpisodeTrace& trace, std::size_t shape, const std::string& path);

// The vessel wall in a time series: none, a static file listed at every time, or a moving wall
// whose caller writes (or reuses) a file of its surface at each time.
struct SeriesWall {
  std::string static_file;                      // relative to the .pvd's folder; "" = none (or moving)
  std::function<std::string(double)> file_at;   // a moving wall: the file (relative to the .pvd's
                                                // folder) of its surface at time t, written by the
                                                // callback if needed; or empty
};

// The episode as a ParaView time series: for each recorded wire shape k, at time
// t_k = time_s[wire_shape_frame[k]] (or k seconds when the frames are unknown),
//   part 0: `folder`/wire_<frame>.vtp (write_wire_shape_vtp; <frame> zero-padded to 5 digits, the
//           shape index when the frame is unknown),
//   part 1: the wall: wall.file_at(t_k), or wall.static_file,
// and `pvd_path` (a .pvd collection, pvd_to_xml) listing them. `folder` is relative to the .pvd's
// directory and must exist (writers do not create directories). Returns the paths written: the
// wire files in time order, then the .pvd. Throws std::invalid_argument when the trace has no wire
// shape, ReportError when a file cannot be written.
std::vector<std::string> write_episode_series(const EpisodeTrace& trace, const std::string& pvd_path,
                                              const std::string& folder, const SeriesWall& wall = {});

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
