#pragma once
// Batches of episodes: which (target, seed) pairs `--target N|all|random --episodes K --seed S`
// means, running them on several threads, and the JSON summary navigate --json prints.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lib/report/trajectory.hpp"
#include "lib/runner/controller.hpp"
#include "lib/runner/run_episode.hpp"
#include "task/navigation_task.hpp"

namespace gw {

struct EpisodeRequest {
  int anatomy = 0;
  int target_id = 0;
  std::uint64_t seed = 0;
};

// Episode k gets seed `seed + k`, so any episode of a batch is re-run alone with --episodes 1
// --seed S+k. Targets: "N" -> K episodes on N; "all" -> K episodes on every target (target-major);
// "random" -> K episodes, each target drawn from a generator seeded with `seed`.
// Throws std::invalid_argument naming the valid targets for an unknown number or bad spec.
std::vector<EpisodeRequest> plan_episodes(const NavigationTask& task, int anatomy, const std::string& target_spec,
                                          int episodes, std::uint64_t seed);

// Runs every request (results in request order). Each worker thread gets its own controller from
// `make_controller`; `progress(done, total)` is called from the workers after each episode.
std::vector<EpisodeTrace> run_batch(const NavigationTask& task, const std::vector<EpisodeRequest>& requests,
                                    const std::function<std::unique_ptr<Controller>()>& make_controller,
                                    int threads, const TraceOptions& options,
                                    const std::function<void(int, int)>& progress = {});

// A wrong-branch loss where the tip folded over first: in the last kFoldWindowS seconds before the
// loss the tip's distal tangent pointed back down the vessel (theta_t_1 = t_1 . c_1 below
// kFoldedTheta). Seen on the deformed coronary: a tip caught on the wall while the wire is turned
// buckles and snaps back, and the folded wire goes into the wrong branch whatever omega was at the
// fork. False for any other outcome or a trace without observations.
inline constexpr double kFoldedTheta = -0.5;
inline constexpr double kFoldWindowS = 1.0;
bool tip_folded_before_loss(const EpisodeTrace& trace);

// {"episodes", "successes", "success_rate", "outcomes": {outcome: count}, "results": [per episode:
// anatomy, controller, target, seed, outcome, detail, steps, sim_time_s, and for a wrong branch
// omega_at_loss (EpisodeTrace) and "folded" (tip_folded_before_loss), "force" (episode_force, N) and with
// recovery "recovery": {attempts_allowed, attempts, outcome, detail, steps, procedure_time_s, force}],
// "force": {mean_peak_node_N, share_peak_node_over_1_5N, mean_peak_total_N, share_peak_total_over_1_5N,
// mean_peak_tip_N, share_peak_tip_over_1_5N, mean_mean_total_N}, "successes_tip_within_1_5N" (successes whose peak
// tip force stayed within 1.5 N), and with recovery "recovery": {attempts_allowed, episodes, successes,
// successes_tip_within_1_5N, success_rate, outcomes, mean_attempts, mean_procedure_time_s, force}, and with a tip reshape
// (TraceOptions::reshaped) per result "reshape": {tip_curvature_per_mm, tip_length_mm, reshaped, outcome, detail, attempts, steps,
// procedure_time_s, withdrawal_s (when reshaped), force} over both passes and "reshape": {tip_curvature_per_mm, tip_length_mm,
// episodes, successes, success_rate, outcomes, reshaped, mean_procedure_time_s, force}}. Outcome, steps,
// sim_time_s and force are the paper's strict episode's (it ends where the first wrong branch or stall
// ends it), recovery's figures the whole procedure's.
nlohmann::json summarize_episodes(const std::vector<EpisodeTrace>& traces);

// The same summary from the per-episode "results" entries alone (summarize_episodes builds them, then
// calls this): how shards of one row run apart (evaluate --episodes) and joined (--from-json) get the
// counts, force and recovery figures a single run computes, to the bit when the entries are in its order.
nlohmann::json summarize_results(const nlohmann::json& results);

}  // namespace gw
