// bench-centerline: time and accuracy of centerline extraction on every anatomy of the
// committed set (anatomies/index.json) against its ground truth. Prints ONE JSON object.
//   bench-centerline [--index anatomies/index.json] [--root DIR] [--only NAME] [--repeat 3] [--vmtk results.json]
// Times are per extraction (surface already taken in, no cache): the median wall time and the
// CPU time of the same run (the machine may be shared; CPU time is the steadier figure). The
// intake (read, units, repairs: intake_surface) is timed once beside it; file-to-targets CPU time
// is the sum. Units are detected as every app does (a surface in metres is scaled).
// --vmtk merges per-anatomy results of training/guidewire_nav/vmtk_centerline.py.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "base/graph/anatomy_index.hpp"
#include "centerline/compare_centerlines.hpp"
#include "centerline/extract_centerline.hpp"
#include "centerline/intake_surface.hpp"
#include <sys/resource.h>

namespace {

// VMTK's result for one anatomy, measured like ours: its lines (one per inlet-target
// path, so shared trunks count once per path) against the truth. VMTK gives paths, not
// a tree, so only distances, radii and time are comparable.
nlohmann::json vmtk_row(const nlohmann::json& v, const gw::CenterlineGraph& truth) {
  if (v.contains("error")) return {{"error", v["error"]}};
  gw::CenterlineGraph g;
  for (const auto& line : v.at("lines")) {
    gw::CenterlineBranch b;
    b.id = static_cast<int>(g.branches.size());
    for (const auto& p : line.at("points")) b.points.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    b.radii = line.at("radii").get<std::vector<double>>();
    if (b.points.empty() || b.radii.size() != b.points.size()) continue;
    g.branches.push_back(std::move(b));
  }
  if (g.branches.empty()) return {{"error", "no centerline"}};
  g.inlet.position = g.branches[0].points.front();
  const gw::CenterlineAccuracy a = gw::compare_centerlines(g, truth);
  return {{"seconds_wall", v.value("seconds", 0.0)},
          {"points", a.points},
          {"mean_distance_over_radius", a.mean_distance},
          {"p95_distance_over_radius", a.p95_distance},
          {"max_distance_over_radius", a.max_distance},
          {"mean_radius_error", a.mean_radius_error},
          {"p95_radius_error", a.p95_radius_error}};
}

// Peak resident memory of this process so far (MB): the largest anatomy's footprint when the
// index is ordered by size, or run with --only.
double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;
}

// --vmtk's results by anatomy name (an empty object without the flag); throws when the file cannot be opened.
nlohmann::json read_vmtk_results(const std::string& vmtk) {
  nlohmann::json vmtk_results = nlohmann::json::object();
  if (!vmtk.empty()) {
    std::ifstream in(vmtk);
    if (!in) throw std::runtime_error(vmtk + ": cannot open");
    vmtk_results = nlohmann::json::parse(in);
  }
  return vmtk_results;
}

// `repeat` extractions of the surface: the last one's graph and stats, and the median (wall, cpu) seconds.
std::pair<double, double> timed_extractions(const gw::ClosedSurface& surface, const gw::CenterlineOptions& options,
                                            int repeat, gw::CenterlineGraph& graph, gw::CenterlineStats& stats) {
  std::vector<std::pair<double, double>> times;  // wall, cpu
  for (int r = 0; r < repeat; ++r) {
    const auto w0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    graph = gw::extract_centerline(surface, options, &stats);
    times.emplace_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count(),
                       double(std::clock() - c0) / CLOCKS_PER_SEC);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

// One anatomy's row: intake and extraction times, MCF stats, accuracy against the truth, VMTK's beside
// it when vmtk_results has the anatomy, and the peak memory so far.
nlohmann::json anatomy_row(const gw::AnatomyEntry& a, int repeat, const nlohmann::json& vmtk_results) {
  // From the file to a closed surface (load, units, repairs): timed once, reported apart.
  const auto i0 = std::chrono::steady_clock::now();
  const std::clock_t ic0 = std::clock();
  const gw::IntakeSurface surface = gw::intake_surface(a.mesh);
  const double intake_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - i0).count();
  const double intake_cpu = double(std::clock() - ic0) / CLOCKS_PER_SEC;
  const gw::CenterlineGraph truth = gw::read_centerline(a.truth);
  gw::CenterlineOptions options;
  options.inlet = truth.inlet.position;
  gw::CenterlineGraph graph;
  gw::CenterlineStats stats;
  const auto median = timed_extractions(surface.closed, options, repeat, graph, stats);
  nlohmann::json row = {{"name", a.name},
                        {"set", a.set},
                        {"faces", surface.input.faces},
                        {"repairs", surface.repairs},
                        {"seconds_intake_wall", intake_wall},
                        {"seconds_intake_cpu", intake_cpu},
                        {"seconds_file_to_targets_cpu", intake_cpu + median.second},
                        {"mcf_faces", stats.skeleton_faces},
                        {"mcf_passes", stats.skeleton_passes},
                        {"seconds_wall", median.first},
                        {"seconds_cpu", median.second},
                        {"seconds_prepare", stats.seconds_prepare},
                        {"seconds_skeleton", stats.seconds_skeleton},
                        {"seconds_graph", stats.seconds_graph},
                        {"accuracy", nlohmann::json::parse(gw::accuracy_to_json(gw::compare_centerlines(graph, truth)))}};
  if (vmtk_results.contains(a.name)) row["vmtk"] = vmtk_row(vmtk_results[a.name], truth);
  row["peak_rss_mb_so_far"] = peak_rss_mb();
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Benchmark centerline extraction against the anatomies' ground truth (one JSON object)"};
  std::string index = "anatomies/index.json", root, vmtk, only;
  int repeat = 3;
  app.add_option("--index", index, "anatomy index");
  app.add_option("--root", root, "folder the index's paths are relative to (default: the index's parent folder's parent)");
  app.add_option("--only", only, "benchmark only the anatomy with this name");
  app.add_option("--repeat", repeat, "extractions per anatomy (median time reported)")->check(CLI::Range(1, 100));
  app.add_option("--vmtk", vmtk, "JSON from vmtk_centerline.py to report side by side");
  CLI11_PARSE(app, argc, argv);
  try {
    const nlohmann::json vmtk_results = read_vmtk_results(vmtk);
    nlohmann::json out;
    out["benchmark"] = "centerline";
    out["hardware_threads"] = std::thread::hardware_concurrency();
    out["anatomies"] = nlohmann::json::array();
    for (const auto& a : gw::read_anatomy_index(index, root)) {
      if (!only.empty() && a.name != only) continue;
      out["anatomies"].push_back(anatomy_row(a, repeat, vmtk_results));
    }
    std::cout << out.dump() << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
