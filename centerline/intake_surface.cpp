#include "centerline/intake_surface.hpp"

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/graph/declared_coordinate_space.hpp"
#include "base/mesh/load_mesh.hpp"

namespace gw {

IntakeSurface intake_surface(const std::string& path, const IntakeOptions& options) {
  if (options.scale < 0 || !std::isfinite(options.scale))
    throw MeshError(path + ": scale must be a positive finite number (or 0 for automatic), got " +
                    std::to_string(options.scale));
  IntakeSurface out;
  out.path = path;
  out.requested_scale = options.scale;
  const auto t0 = std::chrono::steady_clock::now();
  TriangleMesh mesh = load_mesh(path);  // throws MeshError for unreadable files
  out.stage_seconds.emplace_back("load", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

  // frame: 3D Slicer writes models in LPS and says so; the project (and Slicer's curves read by
  // read_centerline) work in RAS
  if (declared_coordinate_space(path) == "LPS") {
    mesh.V.col(0) *= -1.0;
    mesh.V.col(1) *= -1.0;
    out.repairs.push_back("the file declares SPACE=LPS (3D Slicer): converted to RAS (x and y negated)");
  }
  // units
  if (!mesh.V.allFinite()) throw MeshError(path + ": " + validate_mesh(mesh).errors.front());
  const double extent = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).maxCoeff();
  if (options.scale > 0) {
    out.scale = options.scale;
  } else if (extent > 0 && extent < options.metres_below) {
    out.scale = 1000.0;
    std::ostringstream line;
    line << "the surface is " << extent << " units across, too small for millimetres: read as metres and "
         << "scaled by 1000 (--scale overrides)";
    out.repairs.push_back(line.str());
  }
  mesh.V *= out.scale;
  out.input = validate_mesh(mesh);
  if (!out.input.ok()) throw MeshError(path + ": " + out.input.errors.front());
  // Holes, joins and pieces are repaired below; a unit suspicion that is left (e.g. centimetres,
  // which an extent cannot tell from a small phantom in mm) stays a warning.
  for (const std::string& w : out.input.warnings)
    if (w.find("units across") != std::string::npos) out.warnings.push_back(w);

  // repair
  try {
    out.closed = close_surface(mesh, options.repair);
  } catch (const std::runtime_error& e) {
    throw MeshError(path + ": " + e.what());
  }
  out.repairs.insert(out.repairs.end(), out.closed.repairs.begin(), out.closed.repairs.end());
  out.stage_seconds.insert(out.stage_seconds.end(), out.closed.stage_seconds.begin(), out.closed.stage_seconds.end());
  out.wall = out.closed.repairs.empty() ? std::move(mesh) : out.closed.mesh;
  return out;
}

std::string intake_report_json(const IntakeSurface& s) {
  const ClosedSurface& c = s.closed;
  nlohmann::json j = {{"file", s.path},
                      {"scale", s.scale},
                      {"scale_detected", s.requested_scale == 0.0 && s.scale != 1.0},
                      {"repairs", s.repairs},
                      {"warnings", s.warnings},
                      {"input",
                       {{"faces", s.input.faces},
                        {"boundary_loops", s.input.boundary_loops},
                        {"non_manifold_edges", s.input.non_manifold_edges},
                        {"components", s.input.components},
                        {"volume_mm3", s.input.volume}}},
                      {"output",
                       {{"faces", s.wall.F.rows()},
                        {"flipped", c.flipped},
                        {"dropped_islands", c.dropped_components},
                        {"dropped_faces", c.dropped_faces},
                        {"open_ends", c.caps.size()},
                        {"fan_caps", c.fan_caps},
                        {"wrapped", c.wrapped},
                        {"staircase_smoothed", c.smoothed},
                        {"alpha_mm", c.wrap_alpha},
                        {"offset_mm", c.wrap_offset},
                        {"volume_mm3", c.volume},
                        {"mean_radius_mm", c.mean_radius()}}}};
  return j.dump();
}

}  // namespace gw
