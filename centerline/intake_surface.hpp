#pragma once
// Mesh intake: the one way every app turns a user's vessel surface file into what the pipeline
// needs. Loads (STL/OBJ/PLY), detects metres, repairs (close_surface: orientation, islands,
// holes, non-manifold joins, alpha wrapping as the fallback) and lists every repair it made.
#include <string>
#include <vector>

#include "centerline/prepare_surface.hpp"
#include "base/mesh/triangle_mesh.hpp"
#include "base/mesh/validate_mesh.hpp"

namespace gw {

struct IntakeOptions {
  // > 0: multiply coordinates by this (file units -> mm), as given. 0: automatic: a surface whose
  // largest bounding-box side is below `metres_below` (a vessel tree is not 2 mm across) is in
  // metres and is scaled by 1000, with a repair line saying so.
  double scale = 0.0;
  double metres_below = 2.0;
  SurfaceRepairOptions repair;
};

struct IntakeSurface {
  std::string path;
  double requested_scale = 0.0;  // IntakeOptions::scale (part of the centerline cache key)
  double scale = 1.0;            // what was applied
  MeshReport input;              // the file as loaded and scaled, before any repair
  ClosedSurface closed;          // closed, one piece, outward, mm: the centerline's input
  // The wall the simulation collides with: the loaded mesh itself when it needed no repair (so a
  // clean file gives exactly its own triangles), else closed.mesh.
  TriangleMesh wall;
  std::vector<std::string> repairs;   // units and every repair of close_surface, one line each
  std::vector<std::string> warnings;  // suspicions that changed nothing (e.g. maybe centimetres)
  std::vector<std::pair<std::string, double>> stage_seconds;  // "load", then close_surface's stages
  bool repaired() const { return !repairs.empty(); }
};

// Throws MeshError "<path>: <problem>" for a file that cannot be read or a surface no repair
// makes usable (empty, NaN coordinates, a single open sheet).
IntakeSurface intake_surface(const std::string& path, const IntakeOptions& options = {});

// The repairs and warnings as one JSON object string:
// {"scale": s, "scale_detected": bool, "repairs": [...], "warnings": [...], "input": {faces,...},
//  "output": {"faces": n, "wrapped": bool, "alpha": a, "offset": o}}
std::string intake_report_json(const IntakeSurface& surface);

}  // namespace gw
