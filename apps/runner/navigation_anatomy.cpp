#include "apps/runner/navigation_anatomy.hpp"

#include <chrono>
#include <filesystem>
#include <memory>

#include "centerline/extract/centerline_cache.hpp"
#include "centerline/graph/inlet_ambiguity.hpp"
#include "engine/mesh/load_mesh.hpp"
#include "engine/scene/vessel_scene.hpp"

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

}  // namespace

NavigationAnatomy load_navigation_anatomy(const std::string& mesh_path, const NavigationAnatomyOptions& options) {
  NavigationAnatomy out;
  LoadMeshOptions load;
  load.scale = options.scale;
  out.mesh = load_valid_mesh(mesh_path, load);

  const auto start = std::chrono::steady_clock::now();
  CenterlineGraph graph;
  if (!options.centerline_path.empty()) {
    graph = read_centerline(options.centerline_path);
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
    graph = cached_extract_centerline(mesh_path, options.scale, extract, cache, nullptr, &hit);
    out.centerline_from_cache = hit;
    out.centerline_source = hit ? "cache" : "extracted";
    if (out.inlet_source == "widest end") out.inlet_warning = inlet_ambiguity(graph);
  }
  out.centerline_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (graph.targets.empty())
    throw std::invalid_argument(mesh_path + ": the centerline has no target (a single tube with no branch end?)");

  auto scene = std::make_shared<const VesselScene>(make_vessel_scene(out.mesh));
  out.anatomy = make_anatomy(anatomy_name_from_path(mesh_path), graph, scene);
  out.anatomy.mesh_path = mesh_path;
  return out;
}

}  // namespace gw
