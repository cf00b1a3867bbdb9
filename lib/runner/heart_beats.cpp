// heart_beats (lib/runner/heart_motion.hpp).
// Input: heart settings. Output: whether they ask for a beating wall (a positive rate or a motion file).
#include "lib/runner/heart_motion.hpp"

namespace gw {

bool heart_beats(const HeartSettings& h) { return h.heart_rate_bpm > 0 || !h.motion_path.empty(); }

}  // namespace gw
