#pragma once
// row_planned: a row's "planned" figure (evaluate --planned-seeds; docs/planning.md), in one of two forms.
// - Per target (row_planned): every target of every anatomy of the row planned with plan_procedure, from seeds
//   first_seed, first_seed + 1, ... until one finds a plan.
// - Per episode (episodes_planned): every episode of the row planned from its own start (its anatomy, target and
//   seed: the start orientation the controllers' columns had), once; so a column's episodes can be read against
//   the plans of the same starts (planned_against_columns).
// Inputs: the planning task (planning_task_config, the row's anatomies), the seeds or the episodes, the plan options,
// threads (plans in parallel), the actor of the controller guides (controller_guides; "" = the search alone).
// Output: {"targets" | "episodes" (how many plans were asked for), "planned" (a plan found), "strict" (a strict one),
// "unreachable" (none, and the course narrows below the wire: ProcedurePlan::why), "force_limit_N",
// "budget_env_steps", "seeds" (per target only), "median_seconds", "per_target" | "per_episode": [{"anatomy",
// "target", "found": strict|procedure|none, "seed", "procedure_time_s", "wrong_entries", "peak_tip_force_N",
// "peak_node_force_N", "tip_to_target_mm", "env_steps", "seconds", "guide" where a guide's procedure was chosen,
// and where none was found "why"}]}, per target in the order of target_key, per episode in the episodes' order.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/runner/episode_batch.hpp"
#include "plan/plan_procedure.hpp"
#include "task/navigation_task.hpp"

namespace gw {

nlohmann::json row_planned(const NavigationTask& planning_task, int seeds, std::uint64_t first_seed,
                           const PlanOptions& options, const std::string& guide_actor, int threads);

nlohmann::json episodes_planned(const NavigationTask& planning_task, const std::vector<EpisodeRequest>& episodes,
                                const PlanOptions& options, const std::string& guide_actor, int threads);

// Several per-episode figures (episodes_planned's outputs: the shards of one row) as one, their episodes in the
// order given, the counts and median time over all of them (without "columns": planned_against_columns).
nlohmann::json join_episodes_planned(const std::vector<const nlohmann::json*>& parts);

// The per-episode plans (episodes_planned's output) against each column of a row (`results`: controller ->
// summary, its "results" one entry per episode), matched by episode_key. Output: controller -> {"episodes" (of the
// column that were planned from the same start, matched), "reached" (the column's strict success), "planned",
// "reached_and_planned", "planned_not_reached" (a plan exists from that start, the controller missed it),
// "reached_not_planned" (the controller reached what the planner did not)}.
nlohmann::json planned_against_columns(const nlohmann::json& planned, const nlohmann::json& results);

}  // namespace gw
