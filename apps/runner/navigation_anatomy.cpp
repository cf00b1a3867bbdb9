#include "apps/runner/navigation_anatomy.hpp"

#include <chrono>
#include <filesystem>
#include <memory>

#include "centerline/extract/centerline_cache.hpp"
#include "engine/mesh/load_mesh.hpp"
#include "engine/scene/vessel_scene.hpp"

namespace gw {

std::string anatomy_name_from_path(const std::string& mesh_path) {
  return std::filesystem::path(mesh_path).stem().string();
}

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
  } else {
    CenterlineOptions extract;
    extract.inlet = options.inlet;
    CacheOptions cache;
    cache.enabled = options.use_cache;
    bool hit = false;
    graph = cached_extract_centerline(mesh_path, options.scale, extract, cache, nullptr, &hit);
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

}  // namespace gw
