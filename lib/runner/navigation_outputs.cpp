#include "lib/runner/navigation_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>

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

namespace {

namespace fs = std::filesystem;

// The output folder and the files written into it, in order: file(name) records dir/name and returns it.
struct OutputFolder {
  std::string dir;
  std::vector<std::string> written;
  std::string file(const std::string& name) {
    written.push_back((fs::path(dir) / name).string());
    return written.back();
  }
};

// A beating wall's series: each distinct shape written once into wall/ (named in wall_files by its key),
// shared by every episode and frame. `out` and `wall_files` must outlive the series.
SeriesWall beating_series_wall(const VesselScene& wall, OutputFolder& out, std::map<long long, std::string>& wall_files) {
  std::error_code ec;
  const fs::path wall_dir = fs::path(out.dir) / "wall";
  fs::create_directories(wall_dir, ec);
  if (ec || !fs::is_directory(wall_dir))
    throw std::runtime_error(wall_dir.string() + ": cannot create output folder: " + ec.message());
  // A periodic motion repeats its shapes (the same phase to 1e-9 of a cycle), a drifting one does not.
  const WallMotion& motion = *wall.motion;
  const bool periodic = motion.kind != WallMotionKind::rigid || motion.velocity.isZero(0.0);
  SeriesWall series_wall;
  series_wall.file_at = [&out, &wall_files, &wall, &motion, periodic](double t) {
    const long long key = periodic ? std::llround(cardiac_phase(motion, t) * 1e9) % 1000000000LL
                                   : std::llround(t * 1e9);
    auto it = wall_files.find(key);
    if (it != wall_files.end()) return it->second;
    char name[64];
    std::snprintf(name, sizeof name, periodic ? "wall/phase_%09lld.vtp" : "wall/time_%012lld.vtp", key);
    write_mesh_vtp(wall_mesh_at(wall, t), out.file(name));
    return wall_files.emplace(key, name).first->second;
  };
  return series_wall;
}

// One pass of an episode as stem.json and stem.vtp, and with wire shapes its ParaView series (stem.pvd, stem/).
void write_pass(OutputFolder& out, const SeriesWall& series_wall, const EpisodeTrace& t, const std::string& stem) {
  std::error_code ec;
  write_trace_json(t, out.file(stem + ".json"));
  write_trace_vtp(t, out.file(stem + ".vtp"));
  if (!t.wire_shapes.empty()) {
    const fs::path folder = fs::path(out.dir) / stem;
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder))
      throw std::runtime_error(folder.string() + ": cannot create output folder: " + ec.message());
    const auto series = write_episode_series(t, (fs::path(out.dir) / (stem + ".pvd")).string(), stem, series_wall);
    out.written.insert(out.written.end(), series.begin(), series.end());
  }
}

// Every episode's passes (episode<K>_target<T>, and _reshaped for a reshape's second pass); returns the
// traces grouped by target for the figures.
std::map<int, std::vector<EpisodeTrace>> write_episodes(OutputFolder& out, const SeriesWall& series_wall,
                                                        const std::vector<EpisodeTrace>& traces) {
  std::map<int, std::vector<EpisodeTrace>> by_target;
  for (std::size_t k = 0; k < traces.size(); ++k) {
    const EpisodeTrace& t = traces[k];
    by_target[t.target_id].push_back(t);
    const std::string stem = "episode" + std::to_string(k) + "_target" + std::to_string(t.target_id);
    write_pass(out, series_wall, t, stem);
    if (!t.reshaped.empty())  // the second pass, from the inlet
      write_pass(out, series_wall, t.reshaped.front(), stem + "_reshaped");
  }
  return by_target;
}

// What the biplane figures are drawn with: the silhouette's mesh, the options and the title lines.
struct FigureSetting {
  TriangleMesh mesh;
  BiplaneOptions options;
  std::vector<std::string> title;
};

// The figures' setting: nav.mesh and the caller's title, or on a beating wall the end-diastolic wall
// outlined at end-systole, and a title line saying so.
FigureSetting figure_setting(const NavigationAnatomy& nav, const std::vector<std::string>& title_lines,
                             const VesselScene* wall, bool beating) {
  FigureSetting f{nav.mesh, BiplaneOptions{}, title_lines};
  if (beating) {
    const double t_ed = wall_time_at_phase(*wall, 0.0);
    const double t_es = wall_time_at_phase(*wall, wall->motion->systole_fraction);
    f.mesh = wall_mesh_at(*wall, t_ed);
    f.options.vessel_label = "wall, end-diastole";
    f.options.wall_outlines.push_back({wall_mesh_at(*wall, t_es), {230, 0, 200}, "wall, end-systole"});
    char line[160];
    std::snprintf(line, sizeof line,
                  "beating %.0f bpm: grey wall at end-diastole (t %.2f s), magenta outline at end-systole (t %.2f s)",
                  wall->motion->heart_rate_bpm, t_ed, t_es);
    f.title.push_back(line);
  }
  return f;
}

// Per target: its planned path (target<T>_path.vtp) and the biplane figure of its episodes (target<T>.png).
void write_target_figures(OutputFolder& out, const CenterlineGraph& graph,
                          const std::map<int, std::vector<EpisodeTrace>>& by_target, const FigureSetting& figure) {
  for (const auto& [target, group] : by_target) {
    const TargetPath path = plan_path(graph, target);
    const std::string stem = "target" + std::to_string(target);
    write_polyline_vtp(path.points, out.file(stem + "_path.vtp"), path.radii);
    render_biplane_png(figure.mesh, graph, path.points, graph.targets[static_cast<std::size_t>(target - 1)], group,
                       figure.title, out.file(stem + ".png"), figure.options);
  }
}

}  // namespace

std::vector<std::string> write_navigation_outputs(const std::string& dir, const NavigationAnatomy& nav,
                                                  const std::vector<EpisodeTrace>& traces,
                                                  const std::vector<std::string>& title_lines,
                                                  const VesselScene* wall) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw std::runtime_error(dir + ": cannot create output folder: " + ec.message());
  OutputFolder out{dir, {}};
  const bool beating = wall && wall->motion;
  const CenterlineGraph& graph = nav.anatomy.graph;
  write_mesh_vtp(beating ? wall->mesh : nav.mesh, out.file("vessel.vtp"));
  write_centerline_vtp(graph, out.file("centerline.vtp"));

  // A beating wall is written once per distinct shape into wall/, shared by every episode and frame.
  std::map<long long, std::string> wall_files;  // outlives series_wall, whose callback fills it
  SeriesWall series_wall;
  if (beating) series_wall = beating_series_wall(*wall, out, wall_files);
  else series_wall.static_file = "vessel.vtp";

  const std::map<int, std::vector<EpisodeTrace>> by_target = write_episodes(out, series_wall, traces);
  // A beating wall: the figure's silhouette is the end-diastolic wall, outlined at end-systole.
  write_target_figures(out, graph, by_target, figure_setting(nav, title_lines, wall, beating));
  return std::move(out.written);
}

}  // namespace gw
