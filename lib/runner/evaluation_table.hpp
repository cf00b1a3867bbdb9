#pragma once
// The paper's results table (Scarponi et al., section 3) on our anatomies: every row run with the
// SAC policy and beside it the two baselines (push-only, scripted omega), next to the paper's figure.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "plan/plan_procedure.hpp"
#include "task/anatomy.hpp"
#include "task/task_config.hpp"

namespace gw {

struct EvaluationRow {
  std::string name;                   // e.g. "coronary-like"
  std::vector<std::string> anatomies; // anatomy names in anatomies/index.json; episodes spread evenly
  int episodes = 50;
  double paper_success = 0.0;         // the paper's success rate for this case, in [0, 1]; < 0: a row the
                                      // paper did not have (the junction rows, issue 41)
  bool base_policy = false;           // sensitivity rows: the policy trained on sensitivity/base only
  double heart_rate_bpm = 0;          // > 0: the wall beats at this rate (issue 36; the anatomy's own cardiac
                                      // field, lib/runner/heart_motion.hpp), the course following it
  std::string index;                  // a pool's row (index_row): its index, whose entries' wire and heart rate
                                      // the anatomies keep ("" for the table's rows)
};

// The rows of the paper's table, in its order.
std::vector<EvaluationRow> paper_table();

// The rows of `table` (in its order) whose name contains one of the comma-separated texts of `filter`
// ("" = all), then a row per text that names an anatomy index (*.json, e.g. a gw-anatomy-pool pool): index_row.
// Throws naming a text that matches no row, so a typo is not silently a shorter table.
// A row of every anatomy an index lists (by its truth file, so it needs no --index), 5 episodes each, named
// "pool PATH"; no paper figure. Throws naming the file when it is unreadable or lists nothing.
EvaluationRow index_row(const std::string& index_path);

std::vector<EvaluationRow> select_rows(const std::vector<EvaluationRow>& table, const std::string& filter);

struct EvaluationOptions {
  std::string policy;                 // actor JSON of the shipped policy
  std::string base_policy;            // actor JSON trained on sensitivity/base only ("" = skip those rows)
  std::string index_path;             // anatomies/index.json
  std::vector<std::string> controllers = {"policy", "push-only", "scripted-omega", "scripted-omega-ccw"};
  bool extract_centerlines = true;    // zero-shot pipeline (CGAL MCF); false = ground-truth centerlines
  double episode_scale = 1.0;         // multiply every row's episode count (quick looks: 0.1)
  std::uint64_t seed = 0;
  int threads = 1;
  bool progress = false;              // stderr: episodes done with an ETA (in place on a terminal, else every
                                      // 10 s) and a line per finished row
  // Rows an earlier run finished (its results.json "rows", see resumable_rows): a row of the table
  // whose name is here is kept as it is, not run again (evaluate --resume).
  nlohmann::json finished_rows = nlohmann::json::array();
  // Called after each row with the evaluation so far ({"rows": the finished rows in the table's order,
  // "settings"}): evaluate writes it at once, so an interruption loses no finished row.
  std::function<void(const nlohmann::json&)> on_row;
  // Targets that no controller of a row reached are probed with the rotation schedules
  // (reachability.hpp) from this many seeds each; 0 = do not probe.
  int reachability_seeds = 2;
  // Every target of a row planned with the procedure planner (row_planned.hpp) from up to this many seeds, under
  // `plan` (its force budget and search budget); the row's "planned" figure. 0 = do not plan (the default).
  int planned_seeds = 0;
  // Instead: every episode of the row planned from its own start (episodes_planned), and each column's episodes
  // against those plans ("planned": {..., "columns": planned_against_columns}); planned_seeds is then unused.
  bool planned_per_episode = false;
  PlanOptions plan;
  // The task (evaluate's --task and task flags, lib/runner/task_options.hpp). The controllers' columns run it as
  // it is, each with its actor's layouts (Controller::adapt); the episodes' draw and the reachability probes run it
  // strict: without recovery and force limit.
  TaskConfig task;
  std::string wire_path;                                                // wire parameter JSON ("" = the 0.014" wire)
  double step_time_limit_s = 0.0;  // --step-time-limit (run_episode.hpp, TraceOptions; 0 = none)
  double reshape_tip_length_mm = 0.0;  // --reshape-tip-length L: the reshaped tip's length (0 = the wire's own)
  double reshape_tip_per_mm = 0.0;  // --reshape-tip C (run_episode.hpp, TraceOptions::reshaped; 0 = never): the
                                    // columns also report the procedure with a reshaped second pass ("reshape")
  // evaluate --episodes FIRST:COUNT (issue 40): run only episodes FIRST .. FIRST+COUNT-1 of each row (a
  // shard; the rest of the row's episodes are drawn as ever, so a shard's episodes are the whole run's).
  // Recorded in the settings as "episodes": [FIRST, COUNT]; count < 0: every episode (not recorded).
  int first_episode = 0;
  int episode_count = -1;
};

// How many episodes a run with `episode_scale` gives `row` (all of them, before any --episodes shard).
int scaled_episodes(const EvaluationRow& row, double episode_scale);

// A row's anatomies as the table runs them: centerlines extracted (or the truth when
// !extract_centerlines), the insertion point from each anatomy's truth, named as in the index.
// Throws std::runtime_error naming an anatomy the index lacks or a mesh that cannot be loaded.
std::vector<Anatomy> load_row_anatomies(const EvaluationRow& row, const EvaluationOptions& options);

// Runs the rows (those in options.finished_rows are taken from there) and returns {"rows": [{name, episodes, paper, results: {controller: summary}, notes,
// reachability: [{anatomy, target, reachable, ...}] for the targets no controller reached, ceiling: {episodes,
// reached, reached_by_a_controller, reached_only_by_a_schedule: [{anatomy, target, seed, schedule}],
// reached_by_none: [{anatomy, target, seed}]} (each episode no column reached, re-run from the same start
// with the rotation schedules; both only when reachability_seeds > 0)}], "settings": ...}. Rows whose
// anatomy or policy is missing are kept with a "skipped" reason; a wire file that cannot be loaded throws.
nlohmann::json run_evaluation(const std::vector<EvaluationRow>& rows, const EvaluationOptions& options);

// The "settings" of a results.json run_evaluation writes with `options`: what its episodes depend on
// (policy, base_policy, seed, intermediate_target_mm, push_mm_per_s, wire, centerlines, episode_scale,
// reachability_seeds) and the controllers.
nlohmann::json evaluation_settings(const EvaluationOptions& options);

// The rows of an earlier results.json (`previous`) a run with `options` may keep instead of running
// them again (evaluate --resume): every row except those with a "skipped" reason (they cost nothing
// and may run now). Throws std::invalid_argument naming the first setting that differs from `options`
// (another seed, policy, episode scale, controllers...) or a joined run (--from-json), since a table
// mixing them would mean neither.
nlohmann::json resumable_rows(const nlohmann::json& previous, const EvaluationOptions& options);

// How the table names a target ("coronary T3") and an episode ("coronary T3 seed 7") in its cells,
// failure modes and results.json, so that runs and their columns can be matched by these names.
std::string target_key(const std::string& anatomy, int target);
std::string episode_key(const nlohmann::json& episode);  // an entry of a summary's "results"
// The settings besides the seed that a results.json's episodes depend on: {push_mm_per_s,
// intermediate_target_mm, centerlines, wire, recovery_attempts, recovery_assist, junctions, reshape_tip_per_mm,
// reshape_tip_length_mm, force_limit_N}
// (wire: the parameter file's path as given, "" = the default). Runs that differ in one are different experiments
// (another insertion speed, other centerlines, a recovery or force limit one has and the other not), and a table
// joining them would mean neither. A setting a run did
// not record is the default it ran with; a joined run has its first input's.
nlohmann::json run_task_settings(const nlohmann::json& run);
// How many episodes a results.json row's paper figure is of: the row's own record, else the paper's
// table by name (results.json files written before rows carried it), else 0 (unknown).
int paper_episodes(const nlohmann::json& row);

// The table as Markdown: case | episodes | SAC | push-only | scripted omega (both turn directions) | paper |
// SAC vs paper (Fisher's exact test) | SAC on reachable targets | SAC vs scripted | reached by a controller or
// rotation schedule, then per row the failure modes seen (outcome counts, places, unreachable targets and
// out-of-reach episodes marked) so a short row says why, not only how much.
std::string evaluation_to_markdown(const nlohmann::json& evaluation);

}  // namespace gw
