// attach_wall_motion, vessel_scene_at (engine/scene/moving_wall.hpp).
// Inputs: a (rest) scene, a motion built for its mesh / a time [s]. Outputs: the scene with the motion
// (or, at 0 bpm, the static scene of the frozen shape) / the static scene of the shape at t.
#include <memory>
#include <stdexcept>

#include "engine/scene/moving_wall.hpp"

namespace gw {

VesselScene vessel_scene_at(const VesselScene& scene, double t) {
  if (!scene.motion) return scene;
  TriangleMesh current = scene.mesh;
  for (Eigen::Index i = 0; i < current.V.rows(); ++i)
    current.V.row(i) = wall_vertex_position(*scene.motion, scene.mesh, static_cast<int>(i), t).transpose();
  return make_vessel_scene(current);
}

VesselScene attach_wall_motion(const VesselScene& scene, const WallMotion& motion) {
  if (scene.motion) throw std::invalid_argument("attach_wall_motion: the scene already moves");
  if (motion.vertices != scene.mesh.V.rows())
    throw std::invalid_argument("attach_wall_motion: the motion was built for another mesh (vertex count)");
  VesselScene out = scene;
  out.motion = std::make_shared<const WallMotion>(motion);
  const bool drifts = motion.kind == WallMotionKind::rigid && !motion.velocity.isZero(0);
  if (motion.heart_rate_bpm > 0 || drifts) return out;
  // Frozen: the static scene of that shape. Unmoved vertices (every one, at zero amplitude) give the
  // rest scene itself, not a rebuild.
  bool moved = false;
  for (Eigen::Index i = 0; i < scene.mesh.V.rows() && !moved; ++i)
    moved = wall_vertex_position(motion, scene.mesh, static_cast<int>(i), 0.0) != scene.mesh.V.row(i).transpose();
  return moved ? vessel_scene_at(out, 0.0) : scene;
}

}  // namespace gw
