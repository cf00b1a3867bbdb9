#pragma once
// Several runs of the results table on different seeds joined into one: 50 episodes a row know a rate to
// about +-10 points and pair too few episodes for a sign test; two seed sets double both.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gw {

// `runs` are results.json objects of `evaluate` (names[i] names runs[i] in errors). Rows are matched by
// name and every column's episodes concatenated: counts, outcomes, per-episode results, the ceiling. A
// target counts as unreached (reachability) only if no column reached it in any run. Throws
// std::invalid_argument naming the row, column or episode when the runs do not fit together: a row or
// column missing from one of them, different paper figures, different settings (insertion speed,
// intermediate target, centerlines, wire file: different experiments; run_task_settings), or an episode
// (anatomy, target, seed) in two runs (the same --seed twice would count every episode twice).
// Columns are summarized again from their episodes (summarize_results) and ceiling lists kept in
// episode_key order. Runs that are shards of one run (evaluate --episodes: settings equal but for their
// "episodes" range) join into that run: its settings, no "merged_from"; given in episode order, the join
// is the run's results.json but for wall_time_s (the shards' sum).
nlohmann::json merge_evaluations(const std::vector<nlohmann::json>& runs, const std::vector<std::string>& names);

}  // namespace gw
