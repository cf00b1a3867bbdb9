#pragma once
// One navigation episode driven by a controller, recorded as an EpisodeTrace (lib/report):
// reset -> (observe -> act -> step) until the task says terminated or truncated.
#include <cstdint>

#include "lib/report/trajectory.hpp"
#include "lib/runner/controller.hpp"
#include "task/episode.hpp"
#include "task/navigation_task.hpp"

namespace gw {

struct TraceOptions {
  // Keep the inserted wire polyline every this many env steps, and the last one; 0 = only the last.
  // Tip, time and action are always kept: a few hundred small entries per episode.
  int wire_shape_every = 25;
  // An env step that runs longer than this on the wall clock ends the episode as a "timeout" naming the limit
  // (StepLimits, episode.hpp); 0 = none. Off by default: with it, an outcome can depend on the machine's load.
  double step_time_limit_s = 0.0;
  // Tip reshape (docs/recovery.md): when set, a procedure that does not reach the target (with recovery: its
  // end after the pull-backs; without: the strict episode) goes on as a clinician's would: the wire is withdrawn,
  // its tip reshaped, and it is navigated again from the inlet with the same seed and controller. This task is
  // the second pass's: the first pass's anatomies and settings with the reshaped wire
  // (make_reshaped_task). The second pass is EpisodeTrace::reshaped; the first is recorded as without it.
  const NavigationTask* reshaped = nullptr;
};

// Runs target `target_id` of anatomy `anatomy` (indices into task.anatomies) from `seed` to its end.
// The trace's outcome is "success" | "wrong_branch" | "stuck" | "timeout" | "diverged" with a detail
// (which goal was missed, the physics problem). Throws std::invalid_argument for a bad anatomy/target.
EpisodeTrace run_episode(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed,
                         Controller& controller, const TraceOptions& options = {});

// Inputs: a task, a tip curvature (1/mm) and a tip length (mm; 0 = the wire's own). Output: the same anatomies
// and settings with the wire's tip reshaped to that curvature over that length (the bent distal part; the tip's
// softer material goes with it), for TraceOptions::reshaped. Throws std::invalid_argument unless the curvature is
// a finite number above 0 and the length 0 or a finite number above 0 shorter than the wire.
NavigationTask make_reshaped_task(const NavigationTask& task, double tip_curvature_per_mm, double tip_length_mm = 0.0);

}  // namespace gw
