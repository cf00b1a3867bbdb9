#pragma once
// lead_in: where a controller's episode stopped getting deeper, as the start of a procedure search (docs/planning.md
// "From where a controller got stuck"). The controller runs the episode from its reset in the planning task until
// the episode ends, it enters a wrong child a (kLeadInEntries + 1)-th time or runs kLeadInTimeS past the strict step
// limit (the generalist's task's procedure: 3 pull-backs, 30 s); the step at which the tip's progress along the course
// was deepest is found, and the episode is replayed to back_steps env steps before it (the simulation is
// deterministic, so the replay is the controller's own trajectory). A search from there shows what the controller
// should have done where it wedged, went into a wrong child or stalled: demonstrations at the states it visits
// (DAgger's relabelling, at the state that matters), and a plan that replays from the reset (its first steps are the
// controller's).
// A controller that reaches the target with no step's tip force over force_limit_N needs no search: its whole episode
// is returned (steps = ran, the state its end).
// Input: the planning task, the episode (anatomy, target, seed), the controller (a PlanGuide), back_steps >= 0, the
// plan's force budget.
// Output: the state at the search's start, the controller's actions up to it (per env step, with whether each was
// in control), their peak forces, and what the controller's whole episode did.
#include <cstdint>
#include <string>
#include <vector>

#include "plan/plan_procedure.hpp"

namespace gw {

inline constexpr double kLeadInTimeS = 30.0;  // simulated seconds a lead-in may run past the strict step limit
inline constexpr int kLeadInEntries = 3;      // wrong-child entries a lead-in may pull out of

struct LeadIn {
  EpisodeState state;               // the search's start: `steps` env steps into the controller's episode
  std::vector<Action> actions;      // the controller's, per env step up to the start
  std::vector<bool> in_control;
  int steps = 0;                    // env steps taken to the start (all of them where it reached the target)
  int deepest_step = 0;             // the env step after which the tip's progress was deepest
  int ran = 0;                      // env steps the controller's whole episode ran
  std::string outcome;  // how it ended: "success", "wrong branch" (one entry too many), "time" (the bound), "stuck",
                        // "step limit", "wire exhausted" or the physics' problem
  double peak_tip_mN = 0.0, peak_node_mN = 0.0;  // over the steps up to the start
};

LeadIn lead_in(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed, const PlanGuide& controller,
               int back_steps, double force_limit_N);

}  // namespace gw
