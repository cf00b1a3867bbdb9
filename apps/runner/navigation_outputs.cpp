#include "apps/runner/navigation_outputs.hpp"

#include <filesystem>
#include <map>
#include <stdexcept>

#include "apps/report/biplane_render.hpp"
#include "apps/report/trace_json.hpp"
#include "apps/report/vtp_writer.hpp"

namespace gw {

std::vector<std::string> write_navigation_outputs(const std::string& dir, const NavigationAnatomy& nav,
                                                  const std::vector<EpisodeTrace>& traces,
                                                  const std::vector<std::string>& title_lines) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw std::runtime_error(dir + ": cannot create output folder: " + ec.message());
  std::vector<std::string> written;
  auto file = [&](const std::string& name) {
    written.push_back((fs::path(dir) / name).string());
    return written.back();
  };
  const CenterlineGraph& graph = nav.anatomy.graph;
  write_mesh_vtp(nav.mesh, file("vessel.vtp"));
  write_centerline_vtp(graph, file("centerline.vtp"));

  std::map<int, std::vector<EpisodeTrace>> by_target;
  for (std::size_t k = 0; k < traces.size(); ++k) {
    const EpisodeTrace& t = traces[k];
    by_target[t.target_id].push_back(t);
    const std::string stem = "episode" + std::to_string(k) + "_target" + std::to_string(t.target_id);
    write_trace_json(t, file(stem + ".json"));
    write_trace_vtp(t, file(stem + ".vtp"));
    if (!t.wire_shapes.empty()) write_wire_shapes_vtp(t, file(stem + "_wire.vtp"));
  }
  for (const auto& [target, group] : by_target) {
    const TargetPath path = plan_path(graph, target);
    const std::string stem = "target" + std::to_string(target);
    write_polyline_vtp(path.points, file(stem + "_path.vtp"), path.radii);
    render_biplane_png(nav.mesh, graph, path.points, graph.targets[static_cast<std::size_t>(target - 1)], group,
                       title_lines, file(stem + ".png"));
  }
  return written;
}

}  // namespace gw
