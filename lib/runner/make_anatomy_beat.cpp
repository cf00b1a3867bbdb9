// make_anatomy_beat (lib/runner/heart_motion.hpp).
// Inputs: an anatomy with a static scene, a cardiac motion. Output: the anatomy with its scene moving
// (attach_wall_motion); its graph stays the rest one (the task maps it every step, graph_motion.hpp). A motion
// frozen in a deformed shape (0 bpm at a phase offset) gives a static scene of that shape, and the graph is
// then mapped to it once here.
#include <memory>
#include <stdexcept>

#include "lib/runner/heart_motion.hpp"
#include "engine/scene/moving_wall.hpp"
#include "task/graph_motion.hpp"

namespace gw {

void make_anatomy_beat(Anatomy& anatomy, const CardiacMotion& motion) {
  if (!anatomy.scene) throw std::invalid_argument(anatomy.name + ": no vessel wall to move");
  if (anatomy.scene->motion) throw std::invalid_argument(anatomy.name + ": the wall already moves");
  const WallMotion wall = heart_wall_motion(anatomy.scene->mesh, motion);
  auto scene = std::make_shared<const VesselScene>(attach_wall_motion(*anatomy.scene, wall));
  if (!scene->motion && scene->mesh.V != anatomy.scene->mesh.V) {  // frozen in a deformed shape
    VesselScene moving = *anatomy.scene;
    moving.motion = std::make_shared<const WallMotion>(wall);
    CenterlineGraph frozen;
    graph_at(anatomy.graph, moving, make_graph_motion(anatomy.graph, moving), 0.0, frozen);
    const Anatomy remade = make_anatomy(anatomy.name, frozen, scene);
    anatomy.graph = remade.graph;
    anatomy.branch_lines = remade.branch_lines;
  }
  anatomy.scene = std::move(scene);
}

}  // namespace gw
