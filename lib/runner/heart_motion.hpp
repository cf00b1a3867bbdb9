#pragma once
// The beating heart on the command line (issue 36, docs/beating_heart.md): `--heart-rate BPM [--motion FILE]`
// of navigate, evaluate's beating rows, guidewire-server and the gymnasium environment. Resolves which
// cardiac motion an anatomy's wall follows and attaches it (the task's centerline follows the wall:
// task/graph_motion.hpp).
#include <Eigen/Core>
#include <string>

#include "engine/scene/wall_motion.hpp"
#include "task/anatomy.hpp"

namespace gw {

struct HeartSettings {
  double heart_rate_bpm = 0;  // 0: a static wall (today's runs, bit for bit), unless motion_path gives a rate
  std::string motion_path;    // a motion JSON (load_cardiac_motion); "" = the anatomy's own (resolve_heart_motion)
};

// Whether `h` asks for a beating wall: a positive rate or a motion file.
bool heart_beats(const HeartSettings& h);

struct HeartMotion {
  CardiacMotion motion;
  std::string source;  // the file it came from, and how ("FILE, held at the inlet", "STEM.spec.json deformation,
                       // fixed at the inlet")
};

// Inputs: the anatomy's mesh path, its inlet (the insertion point), the settings. Output: the motion:
//   settings.motion_path when given; else STEM.motion.json beside the mesh; else the "deformation" block of
//   STEM.spec.json beside it (the anatomy generator's field, which must be at phase 0, i.e. the mesh is the
//   rest shape) played over the cycle and held still at the inlet (the guide catheter's frame). A motion file
//   that does not name its held point ("fixed_point") is held at `inlet` too (CardiacMotion::hold_inlet).
// The rate is settings.heart_rate_bpm when positive, else the file's. Throws std::runtime_error naming the
// mesh when no motion is found, a spec's field is not at phase 0, or a file is unreadable.
HeartMotion resolve_heart_motion(const std::string& mesh_path, const Eigen::Vector3d& inlet, const HeartSettings& h);

// Input: a spec's "deformation" block {"center", "axis", "radial_contraction", "axial_shortening",
// "twist_deg_per_cm", "phase"} and the point to hold still. Output: the same map as a CardiacMotion
// (contraction and shortening as fractions of a 1 mm reference). Throws std::runtime_error "<spec>: <problem>".
CardiacMotion cardiac_motion_from_spec(const std::string& spec_path, const Eigen::Vector3d& fixed_point);

// Input: an anatomy with a static scene and a motion. Output: the anatomy's scene replaced by the moving one
// (attach_wall_motion: at 0 bpm the frozen shape's static scene). The rest graph stays: the task maps it.
void make_anatomy_beat(Anatomy& anatomy, const CardiacMotion& motion);

// Inputs: the anatomy (mesh_path, inlet) and the settings. Output: the anatomy beating when heart_beats(h)
// (resolve_heart_motion + make_anatomy_beat), untouched otherwise; the motion's source, or "".
std::string apply_heart_settings(Anatomy& anatomy, const HeartSettings& h);

}  // namespace gw
