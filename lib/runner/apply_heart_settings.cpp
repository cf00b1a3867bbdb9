// apply_heart_settings (lib/runner/heart_motion.hpp).
// Inputs: an anatomy (mesh_path, rest graph's inlet, static scene) and the heart settings. Output: the anatomy
// beating when the settings ask for it (resolve_heart_motion + make_anatomy_beat); the motion's source or "".
#include "lib/runner/heart_motion.hpp"

namespace gw {

std::string apply_heart_settings(Anatomy& anatomy, const HeartSettings& h) {
  if (!heart_beats(h)) return "";
  const HeartMotion m = resolve_heart_motion(anatomy.mesh_path, anatomy.graph.inlet.position, h);
  make_anatomy_beat(anatomy, m.motion);
  return m.source;
}

}  // namespace gw
