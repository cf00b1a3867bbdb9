// heart_wall_motion (engine/scene/wall_motion.hpp).
// Inputs: the rest mesh (the scene's) and a CardiacMotion. Output: its wall motion: the phase surfaces'
// (4D CT; each file loaded with load_mesh and matched to the rest mesh triangle for triangle) or the
// parametric map's. Throws std::runtime_error naming a file that cannot be loaded or does not match, and
// std::invalid_argument for a bad rate or phase (as cardiac_wall_motion does).
#include <stdexcept>
#include <string>

#include "engine/mesh/load_mesh.hpp"
#include "engine/scene/wall_motion.hpp"

namespace gw {

WallMotion heart_wall_motion(const TriangleMesh& rest, const CardiacMotion& params) {
  if (params.phase_surfaces.empty()) return cardiac_wall_motion(rest, params);
  std::vector<Eigen::MatrixX3d> frames;
  for (const std::string& path : params.phase_surfaces) {
    const TriangleMesh phase = load_mesh(path);
    if (phase.V.rows() != rest.V.rows() || phase.F.rows() != rest.F.rows() || phase.F != rest.F)
      throw std::runtime_error(path + ": this phase surface has " + std::to_string(phase.V.rows()) + " vertices and " +
                               std::to_string(phase.F.rows()) + " triangles in another order than the vessel mesh (" +
                               std::to_string(rest.V.rows()) + ", " + std::to_string(rest.F.rows()) +
                               "): phase surfaces must be the same mesh moved (export every phase from one "
                               "segmentation's mesh, e.g. as OBJ or PLY)");
    frames.push_back(phase.V);
  }
  return phase_wall_motion(rest, frames, params.heart_rate_bpm, params.phase_offset);
}

}  // namespace gw
