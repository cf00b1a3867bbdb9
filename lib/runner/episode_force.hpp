#pragma once
// Safety figures of one episode (issue 37 item 4) from its trace's per-frame wall force (mN) in newtons:
// how hard the wire pressed on the vessel wall.
#include <nlohmann/json.hpp>

#include "lib/report/trajectory.hpp"
#include "task/wall_force.hpp"  // kRuptureForceN: peaks above it count as unsafe

namespace gw {

// Inputs: a trace and the frames (first, last] to take (the env steps that led to frames first+1..last).
// Output: {"peak_node_N": the largest single-node force, "peak_total_N": the largest total over the
// nodes, "mean_total_N": the total's mean over the physics steps, "peak_tip_N": the largest force on the
// distal 1 mm}, and with a force limit (the trace's push_held_s) "push_held_s": the simulated time the forward
// push was withheld; an empty object when the trace carries no force or the range holds no frame.
nlohmann::json episode_force(const EpisodeTrace& trace, int first, int last);

}  // namespace gw
