// resolve_heart_motion (lib/runner/heart_motion.hpp).
// Inputs: mesh path, inlet, heart settings. Output: the cardiac motion and where it came from.
#include <filesystem>
#include <stdexcept>

#include "lib/runner/heart_motion.hpp"

namespace gw {

HeartMotion resolve_heart_motion(const std::string& mesh_path, const Eigen::Vector3d& inlet, const HeartSettings& h) {
  HeartMotion out;
  const std::filesystem::path mesh(mesh_path);
  const std::filesystem::path beside = mesh.parent_path() / (mesh.stem().string() + ".motion.json");
  const std::filesystem::path spec = mesh.parent_path() / (mesh.stem().string() + ".spec.json");
  if (!h.motion_path.empty()) {
    out.motion = load_cardiac_motion(h.motion_path);
    out.source = h.motion_path;
  } else if (std::filesystem::exists(beside)) {
    out.motion = load_cardiac_motion(beside.string());
    out.source = beside.string();
  } else if (std::filesystem::exists(spec)) {
    out.motion = cardiac_motion_from_spec(spec.string(), inlet);
    out.source = spec.string() + " deformation, fixed at the inlet";
  } else {
    throw std::runtime_error(mesh_path + ": no cardiac motion for this mesh (no " + beside.filename().string() +
                             " or " + spec.filename().string() + " with a \"deformation\" beside it): give --motion FILE");
  }
  if (out.motion.hold_inlet) {  // a motion file's default: the guide catheter's frame
    out.motion.has_fixed_point = true;
    out.motion.fixed_point = inlet;
    out.source += ", held at the inlet";
  }
  if (h.heart_rate_bpm > 0) out.motion.heart_rate_bpm = h.heart_rate_bpm;
  return out;
}

}  // namespace gw
