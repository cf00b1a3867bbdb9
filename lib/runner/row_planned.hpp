#pragma once
// row_planned: a row's "planned" figure (evaluate --planned-seeds; docs/planning.md): every target of every anatomy
// of the row planned with plan_procedure, from seeds first_seed, first_seed + 1, ... until one finds a plan.
// Inputs: the planning task (planning_task_config, the row's anatomies), seeds, the plan options, threads (targets in
// parallel), the actor of the controller guides (controller_guides; "" = the search alone). Output: {"targets", "planned" (a plan found), "strict" (a strict one), "unreachable" (none, and the
// course narrows below the wire: ProcedurePlan::why), "force_limit_N", "budget_env_steps", "seeds", "median_seconds",
// "per_target": [{"anatomy", "target", "found": strict|procedure|none, "seed", "procedure_time_s", "wrong_entries",
// "peak_tip_force_N", "peak_node_force_N", "tip_to_target_mm", "env_steps", "seconds", "guide" where a guide's
// procedure was chosen, and where none was found "why"}]} in the order of target_key.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "plan/plan_procedure.hpp"
#include "task/navigation_task.hpp"

namespace gw {

nlohmann::json row_planned(const NavigationTask& planning_task, int seeds, std::uint64_t first_seed,
                           const PlanOptions& options, const std::string& guide_actor, int threads);

}  // namespace gw
