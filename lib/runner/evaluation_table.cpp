#include "lib/runner/evaluation_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <unistd.h>

#include "base/graph/anatomy_index.hpp"
#include "lib/runner/controller.hpp"
#include "lib/runner/episode_batch.hpp"
#include "lib/runner/evaluation_progress.hpp"
#include "lib/runner/heart_motion.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "lib/runner/reachability.hpp"
#include "lib/runner/row_planned.hpp"
#include "lib/runner/success_statistics.hpp"
#include "plan/planning_task.hpp"
#include "policy/load_actor.hpp"
#include "task/navigation_task.hpp"
#include "task/task_config_json.hpp"
#include "engine/wire/wire_params.hpp"

namespace gw {

std::vector<EvaluationRow> paper_table() {
  return {
      {"training anatomies", {"t1_straight_y", "t2_curved_straight_exit", "t3_out_of_plane_steep", "t4_s_curving_back"},
       100, 0.95, false},
      {"sensitivity: rotation", {"rotated"}, 50, 1.00, true},
      {"sensitivity: translation", {"translated"}, 50, 1.00, true},
      {"sensitivity: var1", {"var1"}, 50, 1.00, true},
      {"sensitivity: var2", {"var2"}, 50, 0.62, true},
      {"sensitivity: var3", {"var3"}, 50, 0.86, true},
      {"tree of training patterns", {"training_patterns_tree"}, 50, 0.98, false},
      {"unseen 4-bifurcation tree", {"unseen_4_bifurcations"}, 50, 1.00, false},
      {"coronary-like", {"coronary"}, 50, 0.94, false},
      {"deformed coronary", {"coronary_deformed"}, 50, 0.90, false},
      // Beyond the paper (issue 41): junctions the training set never had (anatomies/junctions).
      {"trifurcation tree", {"coronary_trifurcation"}, 50, -1.0, false},
      {"closely spaced forks", {"close_forks"}, 50, -1.0, false},
      // Beyond the paper (issue 36): the coronary tree beating, its generator's deformation field played over
      // the cardiac cycle (docs/beating_heart.md); the paper's deformed coronary row is its frozen end-systole.
      {"beating coronary 60 bpm", {"coronary"}, 50, -1.0, false, 60.0},
      {"beating coronary 100 bpm", {"coronary"}, 50, -1.0, false, 100.0},
      // The junction rows (issue 41) leave side branches on the inner side of a turn, unreachable by design (results/junctions);
      // corrected beside them, the frozen rows kept (anatomies/junctions/make_specs.py).
      {"trifurcation tree (outer side branches)", {"coronary_trifurcation_outer"}, 50, -1.0, false},
      {"closely spaced forks (outer side branches)", {"close_forks_outer"}, 50, -1.0, false},
  };
}

int scaled_episodes(const EvaluationRow& row, double episode_scale) {
  return std::max(1, static_cast<int>(std::lround(row.episodes * episode_scale)));
}

std::string target_key(const std::string& anatomy, int target) { return anatomy + " T" + std::to_string(target); }

std::string episode_key(const nlohmann::json& ep) {
  return target_key(ep["anatomy"].get<std::string>(), ep["target"].get<int>()) + " seed " +
         std::to_string(ep["seed"].get<std::uint64_t>());
}

namespace {

// Episodes spread round-robin over the row's anatomies, each target drawn from a seeded generator.
std::vector<EpisodeRequest> row_requests(const NavigationTask& task, int episodes, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<EpisodeRequest> out;
  for (int k = 0; k < episodes; ++k) {
    const int a = k % static_cast<int>(task.anatomies.size());
    const auto count = static_cast<std::uint64_t>(task.anatomies[static_cast<std::size_t>(a)].graph.targets.size());
    out.push_back({a, 1 + static_cast<int>(rng() % count), seed + static_cast<std::uint64_t>(k)});
  }
  return out;
}


// The targets of a row that no column reached in any episode, probed with the rotation schedules
// (a target some controller reached is reachable by definition and costs nothing).
nlohmann::json row_reachability(const NavigationTask& task, const nlohmann::json& results, int seeds, int threads) {
  std::map<std::string, int> successes;
  std::map<std::string, ReachabilityCase> cases;
  for (const auto& [column, summary] : results.items())
    for (const nlohmann::json& ep : summary["results"]) {
      const std::string key = target_key(ep["anatomy"].get<std::string>(), ep["target"].get<int>());
      successes[key] += ep["outcome"] == "success";
      if (!cases.count(key))
        cases[key] = {find_anatomy(task, ep["anatomy"].get<std::string>()), ep["target"].get<int>()};
    }
  std::vector<std::string> keys;
  std::vector<ReachabilityCase> todo;
  for (const auto& [key, n] : successes)
    if (n == 0) {
      keys.push_back(key);
      todo.push_back(cases[key]);
    }
  nlohmann::json out = nlohmann::json::array();
  if (seeds <= 0 || todo.empty()) return out;
  const std::vector<Reachability> verdicts = probe_reachability(task, todo, seeds, threads);
  for (std::size_t i = 0; i < todo.size(); ++i) {
    nlohmann::json j = to_json(verdicts[i]);
    j["anatomy"] = task.anatomies[static_cast<std::size_t>(todo[i].anatomy)].name;
    j["target"] = todo[i].target_id;
    j["key"] = keys[i];
    out.push_back(j);
  }
  return out;
}

// Per episode (anatomy, target, seed): did some column reach it, and if none did, does some rotation
// schedule from the same start? The action is only the rotation rate, so the share this reaches is what
// a rotation-only controller can be shown to get on these very episodes: a row that falls short of
// the paper although its controllers reach nearly every episode this reaches is the anatomy's, not the
// controller's. Episodes no schedule reaches are listed.
nlohmann::json row_ceiling(const NavigationTask& task, const nlohmann::json& results, int threads) {
  std::map<std::string, bool> reached;
  std::map<std::string, nlohmann::json> start;
  for (const auto& [column, summary] : results.items())
    for (const nlohmann::json& ep : summary["results"]) {
      const std::string key = episode_key(ep);
      reached[key] = reached[key] || ep["outcome"] == "success";
      start[key] = {{"anatomy", ep["anatomy"]}, {"target", ep["target"]}, {"seed", ep["seed"]}};
    }
  std::vector<std::string> keys;
  std::vector<ReachabilityCase> cases;
  int by_controller = 0;
  for (const auto& [key, ok] : reached) {
    if (ok) {
      ++by_controller;
      continue;
    }
    const nlohmann::json& s = start[key];
    keys.push_back(key);
    cases.push_back({find_anatomy(task, s["anatomy"].get<std::string>()), s["target"].get<int>(),
                     s["seed"].get<std::uint64_t>()});
  }
  const std::vector<Reachability> verdicts = probe_reachability(task, cases, 1, threads);
  nlohmann::json by_schedule = nlohmann::json::array(), unreached = nlohmann::json::array();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    nlohmann::json s = start[keys[i]];
    if (!verdicts[i].error.empty()) {
      s["error"] = verdicts[i].error;
      unreached.push_back(s);
    } else if (verdicts[i].reachable) {
      s["schedule"] = verdicts[i].schedule;
      by_schedule.push_back(s);
    } else {
      unreached.push_back(s);
    }
  }
  return {{"episodes", reached.size()},
          {"reached", by_controller + static_cast<int>(by_schedule.size())},
          {"reached_by_a_controller", by_controller},
          {"reached_only_by_a_schedule", by_schedule},
          {"reached_by_none", unreached}};
}

}  // namespace

std::vector<Anatomy> load_row_anatomies(const EvaluationRow& row, const EvaluationOptions& o) {
  std::vector<Anatomy> anatomies;
  // A pool's row (index_row) lists its index's entries by their truth files, in the index's order: entry i's wire
  // and heart rate go with anatomy i.
  const std::vector<AnatomyEntry> pool = row.index.empty() ? std::vector<AnatomyEntry>{} : read_anatomy_index(row.index);
  if (!pool.empty() && pool.size() != row.anatomies.size())
    throw std::runtime_error(row.index + ": the index lists " + std::to_string(pool.size()) + " anatomies, its row " +
                             std::to_string(row.anatomies.size()) + " (the file changed during the run?)");
  for (std::size_t i = 0; i < row.anatomies.size(); ++i) {
    std::vector<AnatomySource> src = resolve_anatomy_sources(row.anatomies[i], o.index_path);
    if (!pool.empty()) {
      src.at(0).wire = pool[i].wire;
      src.at(0).heart_rate_bpm = pool[i].heart_rate_bpm;
    }
    NavigationAnatomyOptions load;
    if (!o.extract_centerlines) load.centerline_path = src.at(0).truth;
    // The insertion point is the user's input, not the extraction's guess: take it from the truth.
    load.inlet = read_centerline(src.at(0).truth).inlet.position;
    NavigationAnatomy nav = load_navigation_anatomy(src.at(0).mesh, load);
    nav.anatomy.name = src.at(0).name;  // the index's name, or a pool row's file stem
    nav.anatomy.wire = load_source_wire(src.at(0));  // an arch pool's aortic wire; nullptr: the run's
    if (row.heart_rate_bpm > 0 || src.at(0).heart_rate_bpm > 0) {  // a beating row, or a beating pool's entry:
      HeartSettings heart;                                             // the anatomy's own field at that rate
      heart.heart_rate_bpm = row.heart_rate_bpm > 0 ? row.heart_rate_bpm : src.at(0).heart_rate_bpm;
      apply_heart_settings(nav.anatomy, heart);
    }
    anatomies.push_back(std::move(nav.anatomy));
  }
  return anatomies;
}

nlohmann::json evaluation_settings(const EvaluationOptions& o) {
  nlohmann::json settings = {{"policy", recorded_path(o.policy)},
          {"base_policy", recorded_path(o.base_policy)},
          {"seed", o.seed},
          {"intermediate_target_mm", o.task.intermediate_target_mm},
          {"push_mm_per_s", o.task.push_mm_per_s},
          {"wire", recorded_path(o.wire_path)},
          {"centerlines", o.extract_centerlines ? "extracted (CGAL MCF)" : "ground truth"},
          {"episode_scale", o.episode_scale},
          {"reachability_seeds", o.reachability_seeds},
          {"controllers", o.controllers}};
  // Only when on, so the results.json files written before recovery existed resume as before.
  if (o.task.recovery_attempts > 0) settings["recovery_attempts"] = o.task.recovery_attempts;
  if (o.task.recovery_assist) settings["recovery_assist"] = true;
  if (o.task.observation.junctions != JunctionModel::kSeparate)
    settings["junctions"] = junction_model_name(o.task.observation.junctions);
  if (o.step_time_limit_s > 0) settings["step_time_limit_s"] = o.step_time_limit_s;
  if (o.planned_seeds > 0 || o.planned_per_episode)
    settings["planned"] = {{"seeds", o.planned_per_episode ? nlohmann::json("episodes")
                                                           : nlohmann::json(o.planned_seeds)},
                           {"force_limit_N", o.plan.force_limit_N},
                           {"budget_env_steps", o.plan.max_env_steps}};
  if (o.reshape_tip_per_mm > 0) settings["reshape_tip_per_mm"] = o.reshape_tip_per_mm;
  if (o.reshape_tip_length_mm > 0) settings["reshape_tip_length_mm"] = o.reshape_tip_length_mm;
  if (o.task.force_limit_N > 0) settings["force_limit_N"] = o.task.force_limit_N;
  if (o.episode_count >= 0) settings["episodes"] = {o.first_episode, o.episode_count};  // a shard (issue 40)
  settings["task"] = task_config_to_json(o.task);  // every field (the keys above are kept for older readers)
  return settings;
}

nlohmann::json resumable_rows(const nlohmann::json& previous, const EvaluationOptions& o) {
  nlohmann::json settings = previous.value("settings", nlohmann::json::object());
  // A run written before paths were recorded relative to the source tree names them absolutely.
  for (const char* key : {"policy", "base_policy", "wire"})
    if (settings.contains(key) && settings[key].is_string())
      settings[key] = recorded_path(settings[key].get<std::string>());
  if (settings.contains("merged_from"))
    throw std::invalid_argument("--resume: the results.json joins several runs (--from-json); only a run of its "
                                "own can be resumed");
  const nlohmann::json now = evaluation_settings(o);
  for (const auto& [key, value] : now.items())
    if ((key != "task" || settings.contains(key)) &&  // runs before the task JSON: their keys above say it
        (!settings.contains(key) || settings[key] != value))
      throw std::invalid_argument("--resume: the earlier run's " + key + " was " +
                                  (settings.contains(key) ? settings[key].dump() : std::string("not recorded")) +
                                  ", this run's is " + value.dump() +
                                  ": give the same settings, or another --out for a new table");
  nlohmann::json rows = nlohmann::json::array();
  for (const nlohmann::json& row : previous.value("rows", nlohmann::json::array()))
    if (!row.contains("skipped")) rows.push_back(row);
  return rows;
}

namespace {

// The row's episodes this run takes: all, or the --episodes shard of them ([first, end) of the row's draw).
std::pair<int, int> shard_range(const EvaluationRow& row, const EvaluationOptions& o) {
  const int all = scaled_episodes(row, o.episode_scale);
  if (o.episode_count < 0) return std::pair<int, int>{0, all};
  const int first = std::min(all, std::max(0, o.first_episode));
  return std::pair<int, int>{first, std::min(all, first + o.episode_count)};
}

// How many episodes of the row this run takes (the shard's length).
int row_episodes(const EvaluationRow& row, const EvaluationOptions& o) {
  const auto [first, end] = shard_range(row, o);
  return end - first;
}

// The actor JSON the row's SAC column runs ("" = none given: the column is skipped).
std::string row_policy(const EvaluationRow& row, const EvaluationOptions& o) {
  return row.base_policy ? o.base_policy : o.policy;
}

// How many columns the row runs: every controller, less SAC where the row has no policy.
int row_columns(const EvaluationRow& row, const EvaluationOptions& o) {
  return static_cast<int>(std::count_if(o.controllers.begin(), o.controllers.end(), [&](const std::string& kind) {
    return kind != "policy" || !row_policy(row, o).empty();
  }));
}

// The finished rows in the table's order, with the settings: what the caller may write after each row.
nlohmann::json table_so_far(const std::vector<EvaluationRow>& rows, const std::map<std::string, nlohmann::json>& finished,
                            const nlohmann::json& settings) {
  nlohmann::json out_rows = nlohmann::json::array();
  for (const EvaluationRow& row : rows)
    if (auto it = finished.find(row.name); it != finished.end()) out_rows.push_back(it->second);
  return nlohmann::json{{"rows", out_rows}, {"settings", settings}};
}

// The episodes the rows not yet finished will run (all their columns): the progress meter's total.
int total_episodes(const std::vector<EvaluationRow>& rows, const std::map<std::string, nlohmann::json>& finished,
                   const EvaluationOptions& o) {
  int total = 0;
  for (const EvaluationRow& row : rows)
    if (!finished.count(row.name)) total += row_episodes(row, o) * row_columns(row, o);
  return total;
}

// A row's record before it runs: name, anatomies, this run's episodes, the paper's figure, empty results and notes.
nlohmann::json row_header(const EvaluationRow& row, int episodes) {
  nlohmann::json r = {{"name", row.name}, {"anatomies", row.anatomies}, {"episodes", episodes},
                      {"paper", row.paper_success}, {"paper_episodes", row.episodes},
                      {"results", nlohmann::json::object()},
                      {"notes", nlohmann::json::array()}};
  if (row.heart_rate_bpm > 0) r["heart_rate_bpm"] = row.heart_rate_bpm;  // only then: older rows stay as they were
  return r;
}

// What every column of a row shares: the wire and anatomies, the strict config and task (the draw and the
// probes), this run's requests and the trace options.
struct RowSetting {
  const WireParams& wire;
  const std::vector<Anatomy>& anatomies;
  const TaskConfig& base_config;
  const NavigationTask& default_task;
  const std::vector<EpisodeRequest>& requests;
  const TraceOptions& trace;
};

// One controller's column: the row's task adapted to its actor (recovery, force limit and reshape as the
// options say), the requests run with progress under `label`. Returns summarize_episodes' JSON.
nlohmann::json run_column(const std::string& kind, const std::string& policy, const RowSetting& s,
                          const std::string& label, const EvaluationOptions& o, ProgressMeter& meter) {
  auto make = [&] { return make_controller(kind, policy); };
  TaskConfig config = s.base_config;
  make()->adapt(config);  // an actor trained on the paper's omega (obs/1) is evaluated with it
  config.recovery_attempts = o.task.recovery_attempts;  // the controllers' columns only: probes stay strict
  config.recovery_assist = o.task.recovery_assist;
  config.force_limit_N = o.task.force_limit_N;
  std::optional<NavigationTask> adapted;
  if (config.observation.omega_plane != s.default_task.config.observation.omega_plane ||
      config.observation.junctions != s.default_task.config.observation.junctions ||
      config.action != s.default_task.config.action || config.recovery_attempts > 0 || config.force_limit_N > 0)
    adapted = make_navigation_task(config, s.wire, s.anatomies);
  const NavigationTask& task = adapted ? *adapted : s.default_task;
  std::optional<NavigationTask> reshaped;  // the controllers' columns only, as recovery
  TraceOptions column_trace = s.trace;
  if (o.reshape_tip_per_mm > 0) {
    reshaped = make_reshaped_task(task, o.reshape_tip_per_mm, o.reshape_tip_length_mm);
    column_trace.reshaped = &*reshaped;
  }
  const std::string where = label + ", " + kind + ": ";
  auto progress = [&](int done, int of) { meter.episode_done(where + std::to_string(done) + "/" + std::to_string(of)); };
  return summarize_episodes(run_batch(task, s.requests, make, o.threads, column_trace, progress));
}

// The row's columns into r["results"] (one per controller; a SAC column without its policy skipped with a
// note), then its reachability, ceiling and planned figures. Throws what loading its anatomies throws.
void run_row_columns(const EvaluationRow& row, const std::string& policy, const std::string& label,
                     const WireParams& wire, const EvaluationOptions& o, ProgressMeter& meter, nlohmann::json& r) {
  const std::vector<Anatomy> anatomies = load_row_anatomies(row, o);
  TaskConfig base_config = o.task;  // strict: the draw and the probes
  base_config.recovery_attempts = 0;
  base_config.recovery_assist = false;
  base_config.force_limit_N = 0.0;
  const NavigationTask default_task = make_navigation_task(base_config, wire, anatomies);
  const auto [first, end] = shard_range(row, o);
  const std::vector<EpisodeRequest> all_requests = row_requests(default_task, end, o.seed);
  const std::vector<EpisodeRequest> requests(all_requests.begin() + first, all_requests.end());
  TraceOptions trace;
  trace.wire_shape_every = 0;
  trace.step_time_limit_s = o.step_time_limit_s;
  const RowSetting setting{wire, anatomies, base_config, default_task, requests, trace};
  for (const std::string& kind : o.controllers) {
    if (kind == "policy" && policy.empty()) {
      r["notes"].push_back("SAC column skipped: no policy trained on sensitivity/base only was given");
      continue;
    }
    if (kind == "policy" && row.base_policy && policy == o.policy)
      r["notes"].push_back("SAC column: the shipped policy (trained on the 4 training anatomies), not one "
                           "trained on sensitivity/base only as in the paper");
    const nlohmann::json summary = run_column(kind, policy, setting, label, o, meter);
    const std::string column = kind == "policy" ? "sac-policy" : kind;
    r["results"][column] = summary;
  }
  r["reachability"] = row_reachability(default_task, r["results"], o.reachability_seeds, o.threads);
  if (o.reachability_seeds > 0) r["ceiling"] = row_ceiling(default_task, r["results"], o.threads);
  if (o.planned_seeds <= 0 && !o.planned_per_episode) return;
  // The planner in its own task: act/2, control everywhere (plan/planning_task.hpp).
  const NavigationTask planning_task = make_navigation_task(planning_task_config(base_config), wire, anatomies);
  if (!o.planned_per_episode) {
    r["planned"] = row_planned(planning_task, o.planned_seeds, o.seed, o.plan, o.policy, o.threads);
    return;
  }
  r["planned"] = episodes_planned(planning_task, requests, o.plan, o.policy, o.threads);
  r["planned"]["columns"] = planned_against_columns(r["planned"], r["results"]);
}

// One row run here: its record with its columns (or "skipped" with the reason) and its wall time; progress
// to `meter`, from which the episodes a skipped row did not run are dropped.
nlohmann::json run_row(const EvaluationRow& row, const std::string& label, const WireParams& wire,
                       const EvaluationOptions& o, ProgressMeter& meter) {
  const auto start = std::chrono::steady_clock::now();
  const int episodes = row_episodes(row, o);
  const int planned = episodes * row_columns(row, o), done_before = meter.done();
  nlohmann::json r = row_header(row, episodes);
  const std::string policy = row_policy(row, o);
  try {
    run_row_columns(row, policy, label, wire, o, meter, r);
  } catch (const std::exception& e) {
    r["skipped"] = e.what();
  }
  meter.drop(planned - (meter.done() - done_before));  // the episodes a skipped row did not run
  r["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.progress)
    meter.line(label + (r.contains("skipped") ? " skipped: " + r["skipped"].get<std::string>()
                                              : " done in " + format_duration(r["wall_time_s"].get<double>())));
  return r;
}

}  // namespace

nlohmann::json run_evaluation(const std::vector<EvaluationRow>& rows, const EvaluationOptions& o) {
  // A bad wire file is the caller's error for every row alike: refused here, not skipped row by row.
  const WireParams wire = o.wire_path.empty() ? default_wire_params() : load_wire_params(o.wire_path);
  // So is a missing or broken actor file of the SAC column (it was a "skipped" row each, and exit 0).
  // ("" = no actor given: the SAC column is skipped, as row_policy says.)
  if (!o.policy.empty() && std::find(o.controllers.begin(), o.controllers.end(), "policy") != o.controllers.end()) {
    try {
      load_actor(o.policy);
    } catch (const std::exception& e) {
      throw std::invalid_argument(std::string("--policy: ") + e.what() +
                                  " (an actor JSON as gw-export writes; without a SAC column: --controllers)");
    }
  }
  const nlohmann::json settings = evaluation_settings(o);
  std::map<std::string, nlohmann::json> finished;  // by name: kept from an earlier run, then the rows run here
  for (const nlohmann::json& row : o.finished_rows) finished[row["name"].get<std::string>()] = row;
  ProgressMeter meter(total_episodes(rows, finished, o), o.progress ? stderr : nullptr,
                      o.progress && isatty(fileno(stderr)));
  const std::string of_rows = "/" + std::to_string(rows.size()) + " ";
  int index = 0;
  for (const EvaluationRow& row : rows) {
    const std::string label = "row " + std::to_string(++index) + of_rows + row.name;
    if (finished.count(row.name)) {
      if (o.progress) meter.line(label + ": kept from the earlier run");
      continue;
    }
    finished[row.name] = run_row(row, label, wire, o, meter);
    if (o.on_row) o.on_row(table_so_far(rows, finished, settings));
  }
  return table_so_far(rows, finished, settings);
}

nlohmann::json run_task_settings(const nlohmann::json& run) {
  nlohmann::json s = run.value("settings", nlohmann::json::object());
  if (s.contains("merged_from") && !s["merged_from"].empty()) s = s["merged_from"][0].value("settings", s);
  const TaskConfig defaults;
  return {{"push_mm_per_s", s.value("push_mm_per_s", defaults.push_mm_per_s)},
          {"intermediate_target_mm", s.value("intermediate_target_mm", defaults.intermediate_target_mm)},
          {"centerlines", s.value("centerlines", std::string("extracted (CGAL MCF)"))},
          {"wire", s.value("wire", std::string())},
          {"recovery_attempts", s.value("recovery_attempts", 0)},
          {"recovery_assist", s.value("recovery_assist", false)},
          {"junctions", s.value("junctions", std::string(junction_model_name(JunctionModel::kSeparate)))},
          {"reshape_tip_per_mm", s.value("reshape_tip_per_mm", 0.0)},
          {"reshape_tip_length_mm", s.value("reshape_tip_length_mm", 0.0)},
          {"force_limit_N", s.value("force_limit_N", 0.0)}};
}

EvaluationRow index_row(const std::string& index_path) {
  EvaluationRow row;
  row.name = "pool " + index_path;
  row.index = index_path;
  for (const AnatomyEntry& e : read_anatomy_index(index_path)) {
    // relative to the working directory where it lies below it, so a results.json names no machine's folders
    const std::string rel = std::filesystem::path(e.truth).lexically_relative(std::filesystem::current_path()).string();
    row.anatomies.push_back(rel.empty() || rel.rfind("..", 0) == 0 ? e.truth : rel);
  }
  if (row.anatomies.empty()) throw std::invalid_argument("--rows '" + index_path + "': the index lists no anatomy");
  row.episodes = 5 * static_cast<int>(row.anatomies.size());
  row.paper_success = -1.0;
  return row;
}

std::vector<EvaluationRow> select_rows(const std::vector<EvaluationRow>& table, const std::string& filter) {
  if (filter.empty()) return table;
  const std::vector<std::string> texts = split_commas(filter);
  if (texts.empty()) throw std::invalid_argument("--rows '" + filter + "' names no row");
  std::vector<bool> keep(table.size(), false);
  std::vector<EvaluationRow> pools;
  for (const std::string& t : texts) {
    if (t.size() > 5 && t.compare(t.size() - 5, 5, ".json") == 0) {  // an anatomy index: a row of its own
      pools.push_back(index_row(t));
      continue;
    }
    bool matched = false;
    for (std::size_t i = 0; i < table.size(); ++i)
      if (table[i].name.find(t) != std::string::npos) keep[i] = matched = true;
    if (!matched) throw std::invalid_argument("no row of the table matches --rows '" + t + "'");
  }
  std::vector<EvaluationRow> out;
  for (std::size_t i = 0; i < table.size(); ++i)
    if (keep[i]) out.push_back(table[i]);
  out.insert(out.end(), pools.begin(), pools.end());
  return out;
}

int paper_episodes(const nlohmann::json& row) {
  if (row.contains("paper_episodes")) return row["paper_episodes"].get<int>();
  for (const EvaluationRow& r : paper_table())
    if (r.name == row.value("name", "")) return r.episodes;
  return 0;
}

namespace {

// Keys ("anatomy Tn") of the row's targets that no rotation schedule reached.
std::set<std::string> unreachable_targets(const nlohmann::json& row) {
  std::set<std::string> out;
  if (row.contains("reachability"))
    for (const nlohmann::json& t : row["reachability"])
      if (!t.value("reachable", true) && !t.contains("error")) out.insert(t["key"].get<std::string>());
  return out;
}

// "95% (38/40)", or "—" for no episodes.
std::string share(int ok, int n) {
  if (n == 0) return "—";
  std::ostringstream s;
  s << std::fixed << std::setprecision(0) << 100.0 * ok / n << "% (" << ok << "/" << n << ")";
  return s.str();
}

// SAC's success over the episodes whose target some rotation reaches: "95% (38/40)", or "—".
std::string reachable_percent(const nlohmann::json& row) {
  if (!row["results"].contains("sac-policy") || !row.contains("reachability")) return "—";
  const std::set<std::string> unreachable = unreachable_targets(row);
  int n = 0, ok = 0;
  for (const nlohmann::json& ep : row["results"]["sac-policy"]["results"]) {
    if (unreachable.count(target_key(ep["anatomy"].get<std::string>(), ep["target"].get<int>()))) continue;
    ++n;
    ok += ep["outcome"] == "success";
  }
  return share(ok, n);
}

// Episodes some controller of the row or some rotation schedule reached: "86% (43/50)", or "—".
std::string ceiling_percent(const nlohmann::json& row) {
  if (!row.contains("ceiling")) return "—";
  return share(row["ceiling"]["reached"].get<int>(), row["ceiling"]["episodes"].get<int>());
}

// Keys ("anatomy Tn seed s") of the row's episodes that nothing reached (row_ceiling).
std::set<std::string> out_of_reach_episodes(const nlohmann::json& row) {
  std::set<std::string> out;
  if (row.contains("ceiling"))
    for (const nlohmann::json& ep : row["ceiling"]["reached_by_none"])
      if (!ep.contains("error")) out.insert(episode_key(ep));
  return out;
}

// The 95% Wilson interval of a column's success rate: "76-94%", or "—".
std::string interval(const nlohmann::json& results, const std::string& column) {
  if (!results.contains(column)) return "—";
  const RateInterval ci = wilson_interval(results[column]["successes"].get<int>(), results[column]["episodes"].get<int>());
  std::ostringstream s;
  s << std::lround(100.0 * ci.low) << "-" << std::lround(100.0 * ci.high) << "%";
  return s.str();
}

// "p 0.69", "p 0.002", "p < 0.001": two decimals would print a clear difference (15 against 2 pairs,
// 0.002) as "p 0.00".
std::string p_text(double p) {
  if (p < 0.001) return "p < 0.001";
  std::ostringstream s;
  s << "p " << std::fixed << std::setprecision(p < 0.01 ? 3 : 2) << p;
  return s.str();
}

// SAC against a scripted omega column on the same episodes: "won 2, lost 4 (p 0.69)", or "—".
std::string sac_vs(const nlohmann::json& results, const std::string& column) {
  if (!results.contains("sac-policy") || !results.contains(column)) return "—";
  const PairedComparison c = compare_paired(results["sac-policy"], results[column]);
  if (c.paired == 0) return "—";
  return "won " + std::to_string(c.only_first) + ", lost " + std::to_string(c.only_second) + " (" +
         p_text(c.sign_test_p) + ")";
}

// SAC's rate against the paper's on different episodes: "-8 points (p 0.20)" with Fisher's exact test
// on the two counts (the paper's figure is itself of 50 or 100 episodes), or "—".
// The paper's figure for a row, "—" for a row beyond the paper.
std::string paper_percent(const nlohmann::json& row) {
  const double paper = row["paper"].get<double>();
  return paper < 0 ? "—" : std::to_string(std::lround(100.0 * paper)) + "%";
}

std::string sac_vs_paper(const nlohmann::json& row) {
  const nlohmann::json& res = row["results"];
  const int n_paper = paper_episodes(row);
  if (!res.contains("sac-policy") || n_paper == 0 || row["paper"].get<double>() < 0 ||
      res["sac-policy"]["episodes"].get<int>() == 0)
    return "—";
  const int ok = res["sac-policy"]["successes"].get<int>(), n = res["sac-policy"]["episodes"].get<int>();
  const int ok_paper = static_cast<int>(std::lround(row["paper"].get<double>() * n_paper));
  const long points = std::lround(100.0 * ok / n) - std::lround(100.0 * ok_paper / n_paper);
  return (points > 0 ? "+" : "") + std::to_string(points) + " points (" +
         p_text(fisher_exact_p(ok, n, ok_paper, n_paper)) + ")";
}

// Against the scripted rule, and where the table ran it, the rule turning the other way:
// "won 0, lost 5 (p 0.06); other way: won 1, lost 0 (p 1.00)".
std::string sac_vs_scripted(const nlohmann::json& results) {
  std::string cell = sac_vs(results, "scripted-omega");
  if (results.contains("scripted-omega-ccw")) cell += "; other way: " + sac_vs(results, "scripted-omega-ccw");
  return cell;
}

std::string percent(const nlohmann::json& results, const std::string& column) {
  if (!results.contains(column)) return "—";
  std::ostringstream s;
  s << std::fixed << std::setprecision(0) << 100.0 * results[column]["success_rate"].get<double>() << "%";
  return s.str();
}

// Where a failure happened, from its detail: "goal 2/3" for "entered a wrong branch before goal 2 of 3"
// (the bifurcation on the path), "" when the detail does not say.
std::string failure_place(const std::string& detail) {
  const std::string key = "before goal ";
  const std::size_t at = detail.find(key);
  if (at == std::string::npos) return "";
  std::string place = detail.substr(at + key.size());
  const std::size_t of = place.find(" of ");
  if (of != std::string::npos) place.replace(of, 4, "/");
  return "goal " + place;
}

// A wrong-branch loss counts as "aimed" when omega was at most this when the tip reached the lost
// bifurcation's centre (EpisodeTrace::omega_at_loss): the bend within ~26 degrees of pointing straight
// away from the wrong branch. The scripted controller stops turning at -0.95.
constexpr double kAimedOmega = -0.9;

struct PlaceCount {
  int episodes = 0;
  int measured = 0;  // episodes that carry omega_at_loss
  int aimed = 0;
  int fold_measured = 0;  // episodes that carry "folded" (older results.json files do not)
  int folded = 0;         // the tip folded over before the loss (tip_folded_before_loss)
  int out_of_reach = 0;  // episodes no controller of the row and no rotation schedule reached
};

// "wrong_branch 9 (t3 T1 goal 1/1 x5 aimed 5, t4 T2 goal 1/1 x4 aimed 1), diverged 1 (...)": counts per
// outcome, and per outcome the anatomy, target and bifurcation where they happened, most frequent first;
// for wrong branches, how many of them the controller had aimed (kAimedOmega).
std::string failure_modes(const nlohmann::json& summary, const std::set<std::string>& unreachable,
                          const std::set<std::string>& out_of_reach) {
  std::string text;
  for (const auto& [outcome, count] : summary["outcomes"].items()) {
    if (outcome == "success" || count.get<int>() == 0) continue;
    std::map<std::string, PlaceCount> places;
    if (summary.contains("results"))
      for (const nlohmann::json& ep : summary["results"]) {
        if (ep.value("outcome", "") != outcome) continue;
        std::string place = target_key(ep.value("anatomy", "?"), ep.value("target", 0));
        const bool no_rotation_reaches = unreachable.count(place) > 0;
        const std::string goal = failure_place(ep.value("detail", ""));
        if (!goal.empty()) place += " " + goal;
        if (no_rotation_reaches) place += " [unreachable]";
        PlaceCount& c = places[place];
        ++c.episodes;
        if (ep.contains("seed") && out_of_reach.count(episode_key(ep))) ++c.out_of_reach;
        if (ep.contains("folded") && ep["folded"].is_boolean()) {
          ++c.fold_measured;
          c.folded += ep["folded"].get<bool>();
        }
        if (ep.contains("omega_at_loss") && ep["omega_at_loss"].is_number()) {
          ++c.measured;
          c.aimed += ep["omega_at_loss"].get<double>() <= kAimedOmega;
        }
      }
    std::vector<std::pair<std::string, PlaceCount>> sorted(places.begin(), places.end());
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto& a, const auto& b) { return a.second.episodes > b.second.episodes; });
    text += (text.empty() ? "" : ", ") + outcome + " " + std::to_string(count.get<int>());
    if (!sorted.empty()) {
      text += " (";
      for (std::size_t i = 0; i < sorted.size(); ++i) {
        const PlaceCount& c = sorted[i].second;
        text += (i ? ", " : "") + sorted[i].first + " x" + std::to_string(c.episodes);
        if (c.measured > 0) text += " aimed " + std::to_string(c.aimed);
        if (c.folded > 0)
          text += " folded " + std::to_string(c.folded) +
                  (c.fold_measured < c.episodes ? " of " + std::to_string(c.fold_measured) : "");
        if (c.out_of_reach > 0) text += " out-of-reach " + std::to_string(c.out_of_reach);
      }
      text += ")";
    }
  }
  return text.empty() ? "none" : text;
}

// Wall force and recovery per row and column (summarize_episodes' "force" and "recovery"), or "" when
// no column carries either (results.json files written before them).
std::string safety_and_recovery_table(const nlohmann::json& e) {
  std::ostringstream md;
  bool any = false, recovery = false, reshape = false;
  for (const nlohmann::json& r : e["rows"])
    if (r.contains("results"))
      for (const auto& [column, summary] : r["results"].items()) {
        any = any || summary.contains("force") || summary.contains("recovery") || summary.contains("reshape");
        recovery = recovery || summary.contains("recovery");
        reshape = reshape || summary.contains("reshape");
      }
  if (!any) return "";
  auto fixed = [](double v, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
  };
  auto force_cells = [&](const nlohmann::json& f) {
    if (!f.contains("mean_peak_node_N")) return std::string("— | — | —");
    return fixed(f["mean_peak_node_N"].get<double>(), 2) + " | " + fixed(f["mean_peak_total_N"].get<double>(), 2) +
           " | " + fixed(100.0 * f["share_peak_node_over_1_5N"].get<double>(), 0) + "%";
  };
  md << "\nWall force and recovery (docs/recovery.md). Peak node force: the largest force on one node of the "
        "wire over the episode (the wall's reaction, normal and friction), mean over the episodes; peak total: "
        "the largest sum over the nodes; > 1.5 N: share of episodes whose peak node force exceeds 1.5 N.";
  if (recovery)
    md << " With recovery: the same episodes go on after the strict end (first wrong branch or stall): the "
          "wire is pulled back before the bifurcation and advanced again, at most K times; attempts and "
          "procedure time (simulated) are means over the episodes, force over the whole procedure.";
  if (reshape)
    md << " With reshape: a procedure that still did not reach the target is withdrawn, the wire's tip reshaped "
          "to the curvature (and length) given, and navigated again from the inlet (with the same recovery); reshaped: episodes "
          "that needed the second pass; procedure time: both passes and the withdrawal between them.";
  md << "\n\n| case | column | strict success | peak node force (N) | peak total (N) | > 1.5 N |";
  if (recovery) md << " with recovery | K | attempts | procedure time (s) | peak node (N) | peak total (N) | > 1.5 N |";
  if (reshape) md << " with reshape | tip (1/mm) | reshaped | procedure time (s) | peak node (N) | > 1.5 N |";
  md << "\n|---|---|---|---|---|---|" << (recovery ? "---|---|---|---|---|---|---|" : "")
     << (reshape ? "---|---|---|---|---|---|" : "") << "\n";
  for (const nlohmann::json& r : e["rows"]) {
    if (!r.contains("results")) continue;
    for (const auto& [column, summary] : r["results"].items()) {
      md << "| " << r["name"].get<std::string>() << " | " << column << " | "
         << share(summary["successes"].get<int>(), summary["episodes"].get<int>()) << " | "
         << force_cells(summary.value("force", nlohmann::json::object())) << " |";
      if (recovery) {
        if (!summary.contains("recovery")) {
          md << " — | — | — | — | — | — | — |";
        } else {
          const nlohmann::json& rec = summary["recovery"];
          md << " " << share(rec["successes"].get<int>(), rec["episodes"].get<int>()) << " | "
             << rec["attempts_allowed"].get<int>() << " | " << fixed(rec["mean_attempts"].get<double>(), 2) << " | "
             << fixed(rec["mean_procedure_time_s"].get<double>(), 1) << " | "
             << force_cells(rec.value("force", nlohmann::json::object())) << " |";
        }
      }
      if (reshape) {
        if (!summary.contains("reshape")) {
          md << " — | — | — | — | — | — |";
        } else {
          const nlohmann::json& sh = summary["reshape"];
          const nlohmann::json f = sh.value("force", nlohmann::json::object());
          md << " " << share(sh["successes"].get<int>(), sh["episodes"].get<int>()) << " | "
             << sh["tip_curvature_per_mm"].get<double>()
             << (sh.contains("tip_length_mm") ? ", " + fixed(sh["tip_length_mm"].get<double>(), 0) + " mm" : std::string())
             << " | " << sh["reshaped"].get<int>() << " | "
             << fixed(sh["mean_procedure_time_s"].get<double>(), 1) << " | "
             << (f.contains("mean_peak_node_N") ? fixed(f["mean_peak_node_N"].get<double>(), 2) + " | " +
                                                      fixed(100.0 * f["share_peak_node_over_1_5N"].get<double>(), 0) + "%"
                                                : std::string("— | —"))
             << " |";
        }
      }
      md << "\n";
    }
  }
  return md.str();
}

}  // namespace

namespace {

// A per-target "planned" figure's row of the markdown table (its header first, when `md` is empty).
void planned_targets_markdown(const nlohmann::json& r, std::ostringstream& md) {
  const nlohmann::json& p = r["planned"];
  if (md.tellp() == 0)
    md << "\n## Planned (the procedure planner, docs/planning.md)\n\nEvery target of the row planned (push, pull, "
          "rotate; tip force within " << p["force_limit_N"].get<double>() << " N), from up to "
       << p["seeds"].get<int>() << " seed(s) each, a search budget of " << p["budget_env_steps"].get<long>()
       << " env steps.\n\n| case | targets | planned | strict | not found (target: the tip's nearest approach to it, mm) | "
          "median planning time, s |\n|---|---|---|---|---|---|\n";
  std::string missed;
  for (const nlohmann::json& t : p["per_target"])
    if (t["found"] == "none") {
      std::ostringstream one;
      one << (missed.empty() ? "" : ", ") << target_key(t["anatomy"].get<std::string>(), t["target"].get<int>())
          << ": " << std::fixed << std::setprecision(1) << t["tip_to_target_mm"].get<double>();
      missed += one.str();
    }
  md << "| " << r["name"].get<std::string>() << " | " << p["targets"].get<int>() << " | " << p["planned"].get<int>()
     << " | " << p["strict"].get<int>() << " | " << (missed.empty() ? "—" : missed) << " | " << std::fixed
     << std::setprecision(1) << p["median_seconds"].get<double>() << " |\n";
}

// A per-episode "planned" figure's row: the plans from the episodes' starts, and each column against them.
void planned_episodes_markdown(const nlohmann::json& r, std::ostringstream& md) {
  const nlohmann::json& p = r["planned"];
  if (md.tellp() == 0)
    md << "\n## Planned from every episode's start (the procedure planner, docs/planning.md)\n\nEvery episode of the "
          "row planned from its own start (push, pull, rotate; tip force within " << p["force_limit_N"].get<double>()
       << " N; a search budget of " << p["budget_env_steps"].get<long>() << " env steps); each column: its "
          "episodes reached / the episodes it missed that a plan reaches from the same start.\n\n| case | episodes | "
          "planned | strict | unreachable | columns: reached, missed but planned | median planning time, s |\n"
          "|---|---|---|---|---|---|---|\n";
  std::string columns;
  const nlohmann::json against = p.value("columns", nlohmann::json::object());
  for (const auto& [name, c] : against.items())
    columns += (columns.empty() ? "" : "; ") + name + " " + std::to_string(c["reached"].get<int>()) + ", " +
               std::to_string(c["planned_not_reached"].get<int>());
  md << "| " << r["name"].get<std::string>() << " | " << p["episodes"].get<int>() << " | "
     << p["planned"].get<int>() << " | " << p["strict"].get<int>() << " | " << p["unreachable"].get<int>() << " | "
     << (columns.empty() ? "—" : columns) << " | " << std::fixed << std::setprecision(1)
     << p["median_seconds"].get<double>() << " |\n";
}

}  // namespace

// The rows' "planned" figures (evaluate --planned-seeds), when any row has one: "" otherwise.
std::string planned_markdown(const nlohmann::json& e) {
  std::ostringstream per_target, per_episode;
  for (const nlohmann::json& r : e["rows"]) {
    if (!r.contains("planned")) continue;
    if (r["planned"].contains("per_episode"))
      planned_episodes_markdown(r, per_episode);
    else
      planned_targets_markdown(r, per_target);
  }
  return per_target.str() + per_episode.str();
}

std::string evaluation_to_markdown(const nlohmann::json& e) {
  std::ostringstream md;
  // A run away from the task's defaults says so above its table: its rates are another experiment's.
  const nlohmann::json settings = run_task_settings(e);
  const double push = settings["push_mm_per_s"].get<double>();
  if (push != TaskConfig{}.push_mm_per_s)
    md << "Insertion speed " << push << " mm/s (the default, at which the policies were trained, is "
       << TaskConfig{}.push_mm_per_s << " mm/s).\n\n";
  if (!settings["wire"].get<std::string>().empty())
    md << "Wire parameters from " << settings["wire"].get<std::string>()
       << " (the policies were trained with the default 0.014\" wire, engine/wire/coronary_014.json).\n\n";
  md << "| case | episodes | SAC (ours) | SAC, 95% interval | push-only | scripted omega | "
        "scripted omega, turning the other way | paper | SAC vs paper | SAC, reachable targets | "
        "SAC vs scripted (and the other way), same episodes | reached by a controller or rotation schedule |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& r : e["rows"]) {
    const nlohmann::json& res = r["results"];
    md << "| " << r["name"].get<std::string>() << " | " << r["episodes"].get<int>() << " | "
       << percent(res, "sac-policy") << " | " << interval(res, "sac-policy") << " | " << percent(res, "push-only")
       << " | " << percent(res, "scripted-omega") << " | " << percent(res, "scripted-omega-ccw") << " | "
       << paper_percent(r) << " | " << sac_vs_paper(r) << " | "
       << reachable_percent(r) << " | " << sac_vs_scripted(res) << " | " << ceiling_percent(r) << " |\n";
  }
  md << "\nScripted omega turns at full rate until omega <= -0.95, then holds; omega gives no side, so the "
        "rule turns one fixed way, and the column beside it is the same rule turning the other way (where it "
        "stops, short of -1 on the side it came from, can decide a shallow fork). "
        "SAC, 95% interval: Wilson score interval of SAC's rate over the row's episodes. SAC vs paper: SAC's "
        "rate minus the paper's, and Fisher's exact two-sided test on the two counts (the paper ran 100 "
        "episodes on the training anatomies and 50 on each other row), i.e. whether the difference could be the "
        "luck of both sets of episodes. SAC vs scripted: "
        "episodes SAC reached and the scripted omega controller (then: the one turning the other way) did not "
        "(won) and the reverse (lost), with the "
        "exact two-sided sign test on those (p < 0.05: unlikely to be the luck of the seeds). Reached by a "
        "controller or rotation schedule: episodes (same anatomy, target and start) that some column reached, "
        "or, where none did, one of the 8 rotation schedules of lib/runner/rotation_schedules.hpp; the "
        "action is only the rotation rate, so this is what rotation alone is shown to reach on these "
        "episodes.\n";
  md << safety_and_recovery_table(e);
  md << "\nFailure modes (episodes that did not reach the target, by outcome; in brackets the anatomy, "
        "target and, for a wrong branch, the goal (bifurcation on the path, k of n) it was lost before; "
        "[unreachable]: no controller of the row reached that target and none of "
        "the rotation schedules of lib/runner/rotation_schedules.hpp did either; aimed k: in k of those "
        "episodes omega was <= -0.9 when the tip reached that bifurcation's centre (or when it failed, if "
        "it went in before), i.e. the tip was bent "
        "away from the wrong branch and the wire went in anyway; folded k: in k of those episodes the tip "
        "pointed back down the vessel (theta_1 < -0.5) in the second before the loss: it caught, the wire "
        "buckled and the folded wire went in (\"of m\": only m of them recorded it; older "
        "results.json files do not); out-of-reach k: k of those episodes "
        "neither a controller of the row nor a rotation schedule reached from the same start):\n\n";
  for (const nlohmann::json& r : e["rows"]) {
    md << "- **" << r["name"].get<std::string>() << "**: ";
    if (r.contains("skipped")) {
      md << "skipped: " << r["skipped"].get<std::string>() << "\n";
      continue;
    }
    std::string sep;
    const std::set<std::string> unreachable = unreachable_targets(r), out_of_reach = out_of_reach_episodes(r);
    for (const auto& [column, summary] : r["results"].items()) {
      md << sep << column << ": " << failure_modes(summary, unreachable, out_of_reach);
      sep = "; ";
    }
    for (const auto& note : r["notes"]) md << sep << note.get<std::string>();
    md << "\n";
  }
  md << planned_markdown(e);
  return md.str();
}

}  // namespace gw
