#pragma once
// make_replay_controller: a controller that plays a recorded action sequence back (navigate --replay, a
// procedure plan's "actions"). Input: the actions, one per env step in control, in order. Output: a
// controller named "replay" that returns them one by one from each episode's start; past their end it
// holds the wire still (rotation 0, insertion 0). Same task, anatomy and seed as the recording: the same
// trajectory bit for bit (the simulator is deterministic).
#include <memory>
#include <vector>

#include "lib/runner/controller.hpp"

namespace gw {

std::unique_ptr<Controller> make_replay_controller(std::vector<Action> actions);

}  // namespace gw
