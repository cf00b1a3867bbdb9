// cardiac_phase, cardiac_activation (engine/scene/wall_motion.hpp).
// Inputs: the motion (heart rate, phase offset) and a time [s]; a phase in [0, 1) and the systole
// fraction. Outputs: the phase in [0, 1); the activation s in [0, 1] (1 at end-systole).
#include <cmath>

#include "engine/scene/wall_motion.hpp"

namespace gw {

double cardiac_phase(const WallMotion& m, double t) {
  const double u = m.phase_offset + t * m.heart_rate_bpm / 60.0;
  const double phase = u - std::floor(u);
  return phase < 1.0 ? phase : 0.0;
}

double cardiac_activation(double phase, double systole_fraction) {
  const double s = systole_fraction;
  if (phase < s) return 0.5 * (1.0 - std::cos(M_PI * phase / s));
  return 0.5 * (1.0 + std::cos(M_PI * (phase - s) / (1.0 - s)));
}

}  // namespace gw
