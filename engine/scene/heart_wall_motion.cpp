// heart_wall_motion (engine/scene/wall_motion.hpp).
// Inputs: the rest mesh (the scene's) and a CardiacMotion. Output: its wall motion: the phase surfaces'
// (4D CT; each file loaded with load_mesh and matched to the rest mesh triangle for triangle; with a
// fixed point, each phase moved back so that the point keeps its place) or the parametric map's.
// Throws std::runtime_error naming a file that cannot be loaded or does not match, and
// std::invalid_argument for a bad rate or phase (as cardiac_wall_motion does) or an inlet to hold that was
// not given (hold_inlet without a fixed point).
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/mesh/load_mesh.hpp"
#include "engine/scene/wall_motion.hpp"

namespace gw {

namespace {

// Each phase moved back by the mean displacement of the rest vertices nearest `point` (the inlet's rim
// and cap), so that the point keeps its place on average: the phases seen from a guide catheter engaged
// there (a translation per phase; the surfaces' own shape is unchanged).
void hold_point_still(const TriangleMesh& rest, const Eigen::Vector3d& point, std::vector<Eigen::MatrixX3d>& frames) {
  const int nearest = std::min<int>(32, static_cast<int>(rest.V.rows()));
  std::vector<std::pair<double, int>> by_distance;
  for (Eigen::Index i = 0; i < rest.V.rows(); ++i)
    by_distance.push_back({(rest.V.row(i).transpose() - point).squaredNorm(), static_cast<int>(i)});
  std::partial_sort(by_distance.begin(), by_distance.begin() + nearest, by_distance.end());
  for (Eigen::MatrixX3d& frame : frames) {
    Eigen::RowVector3d shift = Eigen::RowVector3d::Zero();
    for (int k = 0; k < nearest; ++k) shift += frame.row(by_distance[k].second) - rest.V.row(by_distance[k].second);
    frame.rowwise() -= shift / nearest;
  }
}

}  // namespace

WallMotion heart_wall_motion(const TriangleMesh& rest, const CardiacMotion& params) {
  if (params.hold_inlet && !params.has_fixed_point)
    throw std::invalid_argument("wall motion: the motion holds the anatomy's inlet still (\"fixed_point\": \"inlet\", "
                                "a motion file's default) but no inlet was given to hold");
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
  if (params.has_fixed_point) hold_point_still(rest, params.fixed_point, frames);
  return phase_wall_motion(rest, frames, params.heart_rate_bpm, params.phase_offset);
}

}  // namespace gw
