#include "lib/runner/navigation_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "lib/report/biplane_render.hpp"
#include "lib/report/trace_json.hpp"
#include "lib/report/vtp_writer.hpp"
#include "engine/scene/wall_motion.hpp"

namespace gw {

TriangleMesh wall_mesh_at(const VesselScene& scene, double t) {
  TriangleMesh m = scene.mesh;
  if (!scene.motion) return m;
  const WallMotion& motion = *scene.motion;
  const WallTime at = wall_time(motion, t);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v)
    m.V.row(v) = wall_vertex_position(motion, scene.mesh, static_cast<int>(v), at).transpose();
  return m;
}

int wire_shape_stride(const VesselScene* wall, double env_step_s) {
  if (!wall || !wall->motion || !(wall->motion->heart_rate_bpm > 0) || !(env_step_s > 0)) return 25;
  const double period_s = 60.0 / wall->motion->heart_rate_bpm;
  return static_cast<int>(std::clamp<long>(std::lround(period_s / (8.0 * env_step_s)), 1, 25));
}

double wall_time_at_phase(const VesselScene& scene, double phase) {
  if (!scene.motion || !(scene.motion->heart_rate_bpm > 0))
    throw std::invalid_argument("wall_time_at_phase: the wall does not beat");
  const double cycles = phase - scene.motion->phase_offset;
  return (cycles - std::floor(cycles)) * 60.0 / scene.motion->heart_rate_bpm;
}

std::vector<std::string> write_navigation_outputs(const std::string& dir, const NavigationAnatomy& nav,
                                                  const std::vector<EpisodeTrace>& traces,
                                                  const std::vector<std::string>& title_lines,
                                                  const VesselScene* wall) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw std::runtime_error(dir + ": cannot create output folder: " + ec.message());
  std::vector<std::string> written;
  auto file = [&](const std::string& name) {
    written.push_back((fs::path(dir) / name).string());
    return written.back();
  };
  const bool beating = wall && wall->motion;
  const CenterlineGraph& graph = nav.anatomy.graph;
  write_mesh_vtp(beating ? wall->mesh : nav.mesh, file("vessel.vtp"));
  write_centerline_vtp(graph, file("centerline.vtp"));

  // A beating wall is written once per distinct shape into wall/, shared by every episode and frame:
  // a periodic motion repeats its shapes (the same phase to 1e-9 of a cycle), a drifting one does not.
  SeriesWall series_wall;
  std::map<long long, std::string> wall_files;
  if (beating) {
    const fs::path wall_dir = fs::path(dir) / "wall";
    fs::create_directories(wall_dir, ec);
    if (ec || !fs::is_directory(wall_dir))
      throw std::runtime_error(wall_dir.string() + ": cannot create output folder: " + ec.message());
    const WallMotion& motion = *wall->motion;
    const bool periodic = motion.kind != WallMotionKind::rigid || motion.velocity.isZero(0.0);
    series_wall.file_at = [&, periodic](double t) {
      const long long key = periodic ? std::llround(cardiac_phase(motion, t) * 1e9) % 1000000000LL
                                     : std::llround(t * 1e9);
      auto it = wall_files.find(key);
      if (it != wall_files.end()) return it->second;
      char name[64];
      std::snprintf(name, sizeof name, periodic ? "wall/phase_%09lld.vtp" : "wall/time_%012lld.vtp", key);
      write_mesh_vtp(wall_mesh_at(*wall, t), file(name));
      return wall_files.emplace(key, name).first->second;
    };
  } else {
    series_wall.static_file = "vessel.vtp";
  }

  auto write_pass = [&](const EpisodeTrace& t, const std::string& stem) {
    write_trace_json(t, file(stem + ".json"));
    write_trace_vtp(t, file(stem + ".vtp"));
    if (!t.wire_shapes.empty()) {
      const fs::path folder = fs::path(dir) / stem;
      fs::create_directories(folder, ec);
      if (ec || !fs::is_directory(folder))
        throw std::runtime_error(folder.string() + ": cannot create output folder: " + ec.message());
      const auto series = write_episode_series(t, (fs::path(dir) / (stem + ".pvd")).string(), stem, series_wall);
      written.insert(written.end(), series.begin(), series.end());
    }
  };
  std::map<int, std::vector<EpisodeTrace>> by_target;
  for (std::size_t k = 0; k < traces.size(); ++k) {
    const EpisodeTrace& t = traces[k];
    by_target[t.target_id].push_back(t);
    const std::string stem = "episode" + std::to_string(k) + "_target" + std::to_string(t.target_id);
    write_pass(t, stem);
    if (!t.reshaped.empty()) write_pass(t.reshaped.front(), stem + "_reshaped");  // the second pass, from the inlet
  }

  // A beating wall: the figure's silhouette is the end-diastolic wall, outlined at end-systole.
  TriangleMesh figure_mesh = nav.mesh;
  BiplaneOptions options;
  std::vector<std::string> title = title_lines;
  if (beating) {
    const double t_ed = wall_time_at_phase(*wall, 0.0);
    const double t_es = wall_time_at_phase(*wall, wall->motion->systole_fraction);
    figure_mesh = wall_mesh_at(*wall, t_ed);
    options.vessel_label = "wall, end-diastole";
    options.wall_outlines.push_back({wall_mesh_at(*wall, t_es), {230, 0, 200}, "wall, end-systole"});
    char line[160];
    std::snprintf(line, sizeof line,
                  "beating %.0f bpm: grey wall at end-diastole (t %.2f s), magenta outline at end-systole (t %.2f s)",
                  wall->motion->heart_rate_bpm, t_ed, t_es);
    title.push_back(line);
  }
  for (const auto& [target, group] : by_target) {
    const TargetPath path = plan_path(graph, target);
    const std::string stem = "target" + std::to_string(target);
    write_polyline_vtp(path.points, file(stem + "_path.vtp"), path.radii);
    render_biplane_png(figure_mesh, graph, path.points, graph.targets[static_cast<std::size_t>(target - 1)], group,
                       title, file(stem + ".png"), options);
  }
  return written;
}

}  // namespace gw
