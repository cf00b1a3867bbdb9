#pragma once
// Open- and closed-loop rotation schedules: the family that decides whether a target can be reached
// by rotation at all. The task pushes at a constant speed and the action is only the proximal
// rotation rate, so a learned policy can be no better than the best rotation-only controller; when no
// schedule of a varied family reaches a target from any start, a failure there is the wire and the
// anatomy (e.g. a side branch on the inner side of a bend, beyond the tip's lateral reach), not the
// controller. The results table uses this to say why a row falls short.
// (training/guidewire_nav/feasibility.py runs the same family through the socket on chosen cases.)
#include <memory>
#include <string>
#include <vector>

#include "lib/runner/controller.hpp"

namespace gw {

// aim-0.95, aim-0.7    turn at full rate while omega > threshold, then hold (the scripted baseline)
// aim-0.95-ccw         the same, turning the other way
// spin-1 .. spin+1     constant rotation rate (fraction of one turn per second)
// wiggle               a = sin(0.3 k) at env step k, sweeping back and forth
const std::vector<std::string>& rotation_schedule_names();

// The names joined for messages and --help: "aim-0.95, aim-0.7, ..., wiggle".
std::string rotation_schedule_list();

// A fresh controller (schedules with a step counter start at 0). Throws std::invalid_argument naming
// the known schedules for an unknown name.
std::unique_ptr<Controller> make_rotation_schedule(const std::string& name);

}  // namespace gw
