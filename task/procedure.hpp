#pragma once
// The procedure above the strict episode (TaskConfig::recovery_attempts > 0; docs/recovery.md): where the paper's
// episode ends (a wrong branch, a stall) a procedure pulls the wire back and tries again, at most K times, within
// recovery_time_s past the step limit. With 0 attempts none of this runs and the episode is the paper's, bit for bit.
#include "task/episode_stages.hpp"

namespace gw {

// A pull-back's command: the wire withdrawn at recovery_pull_mm_per_s, turned by k * recovery_turn_rad on the k-th.
void procedure_command(const NavigationTask& task, EpisodeState& s, StepCommand& command);

// An env step of a pull-back, after its physics and observation: no end test but the procedure's step limit;
// the actor gets the wire back once the tip is recovery_retract_mm before the bifurcation it was lost at.
StepOutcome retraction_step(const NavigationTask& task, EpisodeState& s, const StepCommand& command,
                            const PhysicsSummary& physics);

// After the strict end test: goes on where the strict episode ends. act/1: a wrong branch, a stall or a folded tip
// starts a pull-back while attempts and time are left. act/2: the actor pulls back itself; an entry into a wrong
// child uses an attempt, the one after the K-th ends the procedure, a stall ends it (with recovery_assist: the
// wrapper's pull-back on a stall, a tip lingering in a wrong child, a standstill after the strict end).
void continue_procedure(const NavigationTask& task, EpisodeState& s, int lost, bool entered, bool stalled,
                        StepOutcome& out);

}  // namespace gw
