#pragma once
// The figure a person reads at a glance after `navigate --out DIR`: the vessel tree in two
// orthogonal projections side by side (like biplane fluoroscopy; see biplane_views.hpp
// for the axes), with
//   - the vessel as a grey silhouette (darker where vessels overlap, like an X-ray),
//   - the planned centerline path in blue, the inlet (teal square), every bifurcation
//     (violet dot, "B<id>" = CenterlineGraph bifurcation id), the other targets (grey ring
//     with number) and the target (red ring, "T<id>"),
//   - each episode's tip trace: orange where the wire was only pushed, green where the
//     agent was in control (or coloured by time, TraceColoring::Time), the final wire
//     shape in black (over the trace for one episode, under the traces for several) and
//     the final tip as a dot in the outcome's colour,
//   - at the top the outcome (SUCCESS / WRONG BRANCH: <detail> / ...; "k/N SUCCESS" for
//     several episodes) and the title lines, a legend at the bottom, a mm scale bar per panel.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "lib/report/biplane_views.hpp"
#include "lib/report/image.hpp"
#include "lib/report/trajectory.hpp"
#include "base/graph/centerline_graph.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

enum class TraceColoring {
  AgentControl,  // orange = push only, green = agent in control
  Time,          // violet (start) -> yellow (end), common time scale over all traces
};

// Another shape of the vessel wall drawn as an outline over the grey silhouette (e.g. a beating
// wall at end-systole over the end-diastolic one), listed in the legend under `label`.
struct WallOutline {
  TriangleMesh mesh;
  Rgb color{220, 60, 0};
  std::string label;
};

struct BiplaneOptions {
  int width = 1400, height = 700;  // pixels; at least 320 x 240
  BiplaneAxes axes = BiplaneAxes::Principal;
  TraceColoring coloring = TraceColoring::AgentControl;
  bool draw_final_wire = true;
  bool label_bifurcations = true;
  bool draw_other_targets = true;
  std::string vessel_label = "vessel";     // the grey silhouette's name in the legend
  std::vector<WallOutline> wall_outlines;  // drawn over the silhouette, under everything else
};

// The image and where each view landed in it (panel rectangles, world -> pixel).
struct BiplaneRender {
  Image image;
  std::array<ViewProjection, 2> views;
};

// Draws the figure. `mesh` may be empty (then the path and graph frame the views);
// `path_points` is the planned route (TargetPath::points); `target` its end
// (graph.targets[id - 1]); `traces` zero or more episodes; `title_lines` free text under
// the outcome line (lines wider than the image are cut with "..."). Views are framed on
// the scene (mesh, graph, path, target), not on the traces, so a diverged trace cannot
// shrink the figure; trace points off the panel are clipped, non-finite ones skipped.
// Throws std::invalid_argument for a size below 320 x 240, an inconsistent trace
// (check_trace) or a scene with no finite point.
BiplaneRender render_biplane(const TriangleMesh& mesh, const CenterlineGraph& graph,
                             const std::vector<Eigen::Vector3d>& path_points, const Terminal& target,
                             const std::vector<EpisodeTrace>& traces, const std::vector<std::string>& title_lines,
                             const BiplaneOptions& options = {});

// render_biplane written as a PNG to `out_path` (atomic; ReportError "<path>: ..." when
// the file cannot be written, nothing half-written).
void render_biplane_png(const TriangleMesh& mesh, const CenterlineGraph& graph,
                        const std::vector<Eigen::Vector3d>& path_points, const Terminal& target,
                        const std::vector<EpisodeTrace>& traces, const std::vector<std::string>& title_lines,
                        const std::string& out_path, const BiplaneOptions& options = {});

}  // namespace gw
