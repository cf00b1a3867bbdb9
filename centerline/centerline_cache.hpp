#pragma once
// Extraction with an on-disk cache keyed by the mesh file's content, so repeated runs
// (navigate, training resets, benchmarks) do not recompute the skeleton.
//
// Cache folder, first that is set: CacheOptions::dir, $GW_CENTERLINE_CACHE,
// $XDG_CACHE_HOME/guidewire-nav/centerline, $HOME/.cache/guidewire-nav/centerline.
// One file per key: <key>.json in the centerline schema. The key is a 64-bit FNV-1a
// hash of the mesh file bytes, the scale, every CenterlineOptions field and the
// pipeline version (kCenterlinePipelineVersion), so a changed mesh or option, or a new
// algorithm, never reads a stale entry. Deleting the folder is always safe.
#include <string>

#include "centerline/extract_centerline.hpp"
#include "centerline/intake_surface.hpp"

namespace gw {

// Bumped whenever the extraction changes its output.
inline constexpr const char* kCenterlinePipelineVersion = "mcf-recentre-14-flat-ends";

struct CacheOptions {
  bool enabled = true;
  std::string dir;  // empty: the environment default above
};

// The folder used when `dir` is empty (see above).
std::string default_centerline_cache_dir();

// 16 hex digits (see above). Throws std::runtime_error "<path>: cannot read mesh file".
std::string centerline_cache_key(const std::string& mesh_path, double scale, const CenterlineOptions& options);

// intake_surface(path, scale) + extract_centerline, through the cache (scale 0: automatic,
// see IntakeOptions; the key holds the scale as given, so "automatic" is its own entry). A corrupt entry
// is recomputed; a cache folder that cannot be written is ignored (the result is still
// returned). `cache_hit` tells whether the result came from the cache; `stats` is only
// filled on a miss. Errors: MeshError/runtime_error "<path>: <problem>".
CenterlineGraph cached_extract_centerline(const std::string& mesh_path, double scale, const CenterlineOptions& options,
                                          const CacheOptions& cache = {}, CenterlineStats* stats = nullptr,
                                          bool* cache_hit = nullptr);

// The same for a surface already taken in (navigate needs it for the wall too): the key is its
// file and requested scale.
CenterlineGraph cached_extract_centerline(const IntakeSurface& surface, const CenterlineOptions& options,
                                          const CacheOptions& cache = {}, CenterlineStats* stats = nullptr,
                                          bool* cache_hit = nullptr);

}  // namespace gw
