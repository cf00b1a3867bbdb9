// centerline: the centerline graph of a vessel surface (CGAL mean-curvature-flow skeleton).
//   centerline --anatomy F.stl [--inlet x,y,z] [--scale S] [--out F.json] [--list]
// Prints the JSON (schema guidewire-nav/centerline/1) on stdout, or writes it to --out;
// --list prints a table of the numbered targets instead. Results are cached by mesh
// content hash (see centerline/centerline_cache.hpp for the folder).
// Bad input: one line "error: FILE: problem" on stderr, exit 1, nothing written.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>

#include "centerline/centerline_cache.hpp"
#include "base/graph/inlet_ambiguity.hpp"
#include "centerline/target_table.hpp"
#include "base/graph/centerline_graph.hpp"
#include "base/util/parse_point.hpp"

namespace {

// Why the skeleton was made twice, or a missed end grafted, in words ("" when neither).
std::string second_pass_note(const gw::CenterlineStats& stats) {
  const std::string finer = stats.skeleton_passes > 1 ? "remeshed finer for " : "";
  if (stats.missed_ends > 0)
    return " (" + finer + std::to_string(stats.missed_ends) + " vessel end(s) the first skeleton missed)";
  return stats.skeleton_passes > 1 ? " (remeshed finer for a thin branch)" : "";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Extract the centerline graph (inlet, numbered targets, branches, bifurcations) of a vessel surface"};
  std::string path, out, inlet_text;
  double scale = 0.0;  // automatic (IntakeOptions)
  bool list = false;
  gw::CenterlineOptions options;
  gw::CacheOptions cache;
  bool no_cache = false, verbose = false;
  app.add_option("--anatomy", path, "vessel surface (.stl, .obj, .ply), millimetres after --scale")->required();
  app.add_option("--inlet", inlet_text, "x,y,z: the terminal nearest this point is the inlet (default: the widest)");
  app.add_option("--scale", scale, "multiply coordinates first (1000 for a mesh in metres); default: automatic, a surface under 2 units "
                 "across is read as metres");
  app.add_option("--out", out, "write the JSON here instead of stdout");
  app.add_flag("--list", list, "print a table of the targets (id, position, path length, bifurcations)");
  app.add_option("--spacing", options.spacing, "point spacing along branches (mm)");
  app.add_option("--cache-dir", cache.dir, "cache folder (default: $GW_CENTERLINE_CACHE, $XDG_CACHE_HOME/guidewire-nav/centerline or ~/.cache/guidewire-nav/centerline)");
  app.add_flag("--no-cache", no_cache, "always recompute; neither read nor write the cache");
  app.add_flag("--verbose", verbose, "report timings and repairs on stderr");
  CLI11_PARSE(app, argc, argv);
  cache.enabled = !no_cache;
  try {
    if (app.count("--scale") && (!(scale > 0) || !std::isfinite(scale)))
      throw std::runtime_error("--scale must be a positive number");
    if (!(options.spacing > 0)) throw std::runtime_error("--spacing must be a positive number");
    if (!inlet_text.empty()) options.inlet = gw::parse_point(inlet_text, "--inlet");
    gw::CenterlineStats stats;
    bool hit = false;
    const gw::CenterlineGraph graph = gw::cached_extract_centerline(path, scale, options, cache, &stats, &hit);
    for (const auto& r : stats.repairs) std::cerr << "repaired: " << path << ": " << r << "\n";
    for (const auto& w : stats.warnings) std::cerr << "warning: " << path << ": " << w << "\n";
    if (!options.inlet)
      if (const std::string w = gw::inlet_ambiguity(graph); !w.empty()) std::cerr << "warning: " << path << ": " << w << "\n";
    if (verbose) {
      if (hit) std::cerr << "centerline: " << path << ": from cache\n";
      else
        std::cerr << "centerline: " << path << ": " << stats.input_faces << " faces -> " << stats.skeleton_faces
                  << " for MCF" << second_pass_note(stats) << "; prepare " << stats.seconds_prepare << " s, skeleton " << stats.seconds_skeleton
                  << " s, graph " << stats.seconds_graph << " s; wall roughness "
                  << (stats.wall_noise > 0 ? std::to_string(stats.wall_noise) + " of the radius (rough-wall section tests)"
                                           : std::string("below 1% of the radius (smooth)"))
                  << "\n";
      if (!hit) {
        std::cerr << "intake: " << path << ":";
        for (const auto& [stage, seconds] : stats.intake_seconds) std::cerr << " " << stage << " " << seconds << " s";
        std::cerr << "\n";
      }
    }
    if (!out.empty()) gw::write_centerline(graph, out);
    if (list) std::cout << gw::format_target_table(graph);
    else if (out.empty()) std::cout << gw::centerline_to_json(graph, 1) << "\n";
    return 0;
  } catch (const std::exception& e) {
    const std::string what = e.what();
    // Messages from the mesh loader already start with the file name.
    std::cerr << "error: " << (what.rfind(path, 0) == 0 || what.rfind("--", 0) == 0 ? what : path + ": " + what) << "\n";
    return 1;
  }
}
