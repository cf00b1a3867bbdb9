#include "lib/runner/navigation_anatomy.hpp"

#include <chrono>
#include <iostream>
#include <filesystem>
#include <memory>

#include "centerline/centerline_cache.hpp"
#include "base/graph/descending_aorta_inlet.hpp"
#include "base/graph/inlet_ambiguity.hpp"
#include "centerline/intake_surface.hpp"
#include "engine/scene/vessel_scene.hpp"
#include "lib/runner/heart_motion.hpp"
#include "task/task_config.hpp"

namespace gw {

std::string anatomy_name_from_path(const std::string& mesh_path) {
  return std::filesystem::path(mesh_path).stem().string();
}

namespace {

// STEM.truth.json beside STEM.stl, or "" when there is none.
std::string truth_sidecar(const std::string& mesh_path) {
  std::filesystem::path p(mesh_path);
  p.replace_extension(".truth.json");
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec) ? p.string() : std::string();
}

void scale_centerline(CenterlineGraph& g, double s) {
  for (CenterlineBranch& b : g.branches) {
    for (Eigen::Vector3d& p : b.points) p *= s;
    for (double& r : b.radii) r *= s;
  }
  for (Bifurcation& b : g.bifurcations) b.position *= s;
  for (auto& t : g.targets) t.position *= s, t.radius *= s;
  g.inlet.position *= s;
  g.inlet.radius *= s;
}

}  // namespace

NavigationAnatomy load_navigation_anatomy(const std::string& mesh_path, const NavigationAnatomyOptions& options) {
  NavigationAnatomy out;
  IntakeOptions intake;
  intake.scale = options.scale;
  const IntakeSurface surface = intake_surface(mesh_path, intake);
  out.mesh = surface.wall;
  out.repairs = surface.repairs;
  out.mesh_warnings = surface.warnings;
  out.intake_report = surface.repaired() || !surface.warnings.empty() ? intake_report_json(surface) : std::string();

  const auto start = std::chrono::steady_clock::now();
  CenterlineGraph graph;
  if (!options.centerline_path.empty()) {
    graph = read_centerline(options.centerline_path);
    // A VMTK .vtp is in the mesh file's units; scale it with the mesh (the project's JSON and
    // Slicer's markups state millimetres).
    if (surface.scale != 1.0 && std::filesystem::path(options.centerline_path).extension() == ".vtp") {
      scale_centerline(graph, surface.scale);
      out.repairs.push_back(options.centerline_path + ": scaled by " + std::to_string(surface.scale) + " with the mesh");
    }
    out.centerline_source = options.centerline_path;
    out.inlet_source = options.centerline_path;
  } else {
    CenterlineOptions extract;
    extract.inlet = options.inlet;
    out.inlet_source = "--inlet";
    if (!extract.inlet) {
      const std::string sidecar = truth_sidecar(mesh_path);
      if (!sidecar.empty()) {
        extract.inlet = read_centerline(sidecar).inlet.position;
        out.inlet_source = sidecar;
      } else {
        out.inlet_source = "widest end";
      }
    }
    CacheOptions cache;
    cache.enabled = options.use_cache;
    bool hit = false;
    graph = cached_extract_centerline(surface, extract, cache, nullptr, &hit);
    if (out.inlet_source == "widest end") {
      if (const auto aorta = descending_aorta_inlet(graph, TaskConfig{}.wide_vessel_radius_mm)) {
        extract.inlet = aorta->position;  // an aortic arch: entered from the groin, at the descending aorta
        graph = cached_extract_centerline(surface, extract, cache, nullptr, &hit);
        out.inlet_source = "descending aorta (an aortic arch: femoral access)";
        (aorta->doubtful ? out.inlet_warning : out.inlet_note) = aorta->note;
      } else {
        out.inlet_warning = inlet_ambiguity(graph);
      }
    }
    out.centerline_from_cache = hit;
    out.centerline_source = hit ? "cache" : "extracted";
  }
  out.centerline_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (graph.targets.empty())
    throw std::invalid_argument(mesh_path + ": the centerline has no target (a single tube with no branch end?)");

  auto scene = std::make_shared<const VesselScene>(make_vessel_scene(out.mesh));
  out.anatomy = make_anatomy(anatomy_name_from_path(mesh_path), graph, scene);
  out.anatomy.mesh_path = mesh_path;
  return out;
}

std::vector<Anatomy> load_indexed_anatomies(const std::string& spec, const std::string& index_path) {
  std::vector<Anatomy> out;
  for (const AnatomySource& s : resolve_anatomy_sources(spec, index_path)) {
    NavigationAnatomyOptions options;
    options.centerline_path = s.truth;
    options.use_cache = false;
    NavigationAnatomy nav = load_navigation_anatomy(s.mesh, options);
    for (const std::string& r : nav.repairs) std::cerr << "repaired: " << s.mesh << ": " << r << "\n";
    nav.anatomy.name = s.name;
    nav.anatomy.wire = load_source_wire(s);
    if (s.heart_rate_bpm > 0) {  // a beating pool's entry: its own field at its own rate
      HeartSettings heart;
      heart.heart_rate_bpm = s.heart_rate_bpm;
      apply_heart_settings(nav.anatomy, heart);
    }
    out.push_back(std::move(nav.anatomy));
  }
  return out;
}

}  // namespace gw
