#include "centerline/centerline_cache.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "centerline/intake_surface.hpp"

namespace gw {
namespace fs = std::filesystem;

std::string default_centerline_cache_dir() {
  if (const char* d = std::getenv("GW_CENTERLINE_CACHE"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/guidewire-nav/centerline";
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : ".") + "/.cache/guidewire-nav/centerline";
}

std::string centerline_cache_key(const std::string& mesh_path, double scale, const CenterlineOptions& o) {
  std::ifstream in(mesh_path, std::ios::binary);
  if (!in) throw std::runtime_error(mesh_path + ": cannot read mesh file");
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&h](const char* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      h ^= static_cast<unsigned char>(data[i]);
      h *= 1099511628211ULL;
    }
  };
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    mix(buffer, static_cast<std::size_t>(in.gcount()));
  }
  std::ostringstream opt;
  opt.precision(17);
  opt << "|" << kCenterlinePipelineVersion << "|" << scale << "|" << o.spacing << "|" << o.edges_per_radius << "|"
      << o.max_skeleton_faces << "|" << o.edges_around_thinnest << "|" << o.spur_factor << "|" << o.merge_factor << "|" << o.smoothing_iterations << "|";
  if (o.inlet) opt << o.inlet->x() << "," << o.inlet->y() << "," << o.inlet->z();
  const std::string tail = opt.str();
  mix(tail.data(), tail.size());
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

namespace {

// The cache around one extraction; `surface` gives the intake result only on a miss.
CenterlineGraph cached(const std::string& path, double scale, const CenterlineOptions& options,
                       const CacheOptions& cache, CenterlineStats* stats, bool* cache_hit,
                       const std::function<const IntakeSurface&()>& surface) {
  if (cache_hit) *cache_hit = false;
  std::string entry;
  if (cache.enabled) {
    const std::string dir = cache.dir.empty() ? default_centerline_cache_dir() : cache.dir;
    entry = dir + "/" + centerline_cache_key(path, scale, options) + ".json";
    std::error_code ec;
    if (fs::exists(entry, ec)) {
      try {
        CenterlineGraph g = read_centerline(entry);
        if (!g.branches.empty()) {
          if (cache_hit) *cache_hit = true;
          return g;
        }
      } catch (const std::exception&) {
        // a corrupt or outdated entry: recompute and overwrite it
      }
    }
  }
  const IntakeSurface& s = surface();
  CenterlineGraph g;
  try {
    g = extract_centerline(s.closed, options, stats);
    // The intake's repairs include close_surface's and the units; its warnings are suspicions.
    if (stats) {
      stats->input_faces = s.input.faces;
      stats->repairs = s.repairs;
      stats->intake_seconds = s.stage_seconds;
      stats->warnings.insert(stats->warnings.begin(), s.warnings.begin(), s.warnings.end());
    }
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  if (!entry.empty()) {
    try {
      std::error_code ec;
      fs::create_directories(fs::path(entry).parent_path(), ec);
      write_centerline(g, entry);  // writes a temporary file and renames: never half an entry
    } catch (const std::exception&) {
      // the cache is an optimisation; a read-only folder must not fail the extraction
    }
  }
  return g;
}

}  // namespace

CenterlineGraph cached_extract_centerline(const std::string& path, double scale, const CenterlineOptions& options,
                                          const CacheOptions& cache, CenterlineStats* stats, bool* cache_hit) {
  std::optional<IntakeSurface> surface;
  IntakeOptions intake;
  intake.scale = scale;
  return cached(path, scale, options, cache, stats, cache_hit, [&]() -> const IntakeSurface& {
    if (!surface) surface = intake_surface(path, intake);
    return *surface;
  });
}

CenterlineGraph cached_extract_centerline(const IntakeSurface& surface, const CenterlineOptions& options,
                                          const CacheOptions& cache, CenterlineStats* stats, bool* cache_hit) {
  return cached(surface.path, surface.requested_scale, options, cache, stats, cache_hit,
                [&]() -> const IntakeSurface& { return surface; });
}

}  // namespace gw
