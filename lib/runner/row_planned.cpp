#include "lib/runner/row_planned.hpp"

#include <algorithm>
#include <atomic>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "base/util/median.hpp"
#include "lib/runner/controller_guides.hpp"
#include "lib/runner/evaluation_table.hpp"

namespace gw {
namespace {

// One plan asked for: a start (anatomy, target) and the seeds to try in turn until one plans.
struct PlannedStart {
  int anatomy = 0, target = 0;
  std::vector<std::uint64_t> seeds;
  std::uint64_t seed = 0;  // the seed of the plan (the last tried where none was found)
  ProcedurePlan plan;
  std::string error;
};

void plan_start(const NavigationTask& task, const PlanOptions& options, const std::string& guide_actor,
                PlannedStart& t) {
  try {
    PlanOptions o = options;  // guides of its own: a controller is not shared between threads
    if (!guide_actor.empty()) o.guides = controller_guides(guide_actor);
    for (std::uint64_t seed : t.seeds) {
      t.seed = seed;
      t.plan = plan_procedure(task, t.anatomy, t.target, t.seed, o);
      if (t.plan.kind != PlanKind::kNone) return;
    }
  } catch (const std::exception& e) {
    t.error = e.what();
  }
}

// Plans every start, `threads` at a time, each start's seeds in order.
void plan_starts(const NavigationTask& task, const PlanOptions& options, const std::string& guide_actor,
                 int threads, std::vector<PlannedStart>& starts) {
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i; (i = next++) < starts.size();) plan_start(task, options, guide_actor, starts[i]);
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < std::max(1, threads); ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

nlohmann::json start_json(const NavigationTask& task, const PlannedStart& t) {
  const ProcedurePlan& p = t.plan;
  nlohmann::json j = {{"anatomy", task.anatomies[static_cast<std::size_t>(t.anatomy)].name},
                      {"target", t.target},
                      {"found", plan_kind_name(p.kind)},
                      {"seed", t.seed},
                      {"procedure_time_s", p.time_s},
                      {"wrong_entries", p.wrong_entries},
                      {"peak_tip_force_N", p.peak_tip_force_N},
                      {"peak_node_force_N", p.peak_node_force_N},
                      {"tip_to_target_mm", p.tip_to_target_mm},
                      {"env_steps", p.strict.env_steps + p.procedure.env_steps},
                      {"seconds", p.strict.seconds + p.procedure.seconds}};
  if (p.kind == PlanKind::kNone && t.error.empty()) j["why"] = p.why;
  if (!p.guide.empty()) j["guide"] = p.guide;
  if (!t.error.empty()) j["error"] = t.error;
  return j;
}

// A figure's counts and median planning time, from its entries under `list` (start_json's), into `figure`: how many
// (under `count`), planned, strict, unreachable (none found because the course narrows below the wire: the
// ProcedurePlan::why that says so). One rule for a figure planned here and for shards joined from their JSON.
void count_entries(nlohmann::json& figure, const std::string& count, const std::string& list) {
  int planned = 0, strict = 0, unreachable = 0;
  std::vector<double> seconds;
  for (const nlohmann::json& e : figure.at(list)) {
    planned += e["found"] != "none";
    strict += e["found"] == "strict";
    unreachable += e.value("why", "").rfind("unreachable:", 0) == 0;
    seconds.push_back(e["seconds"].get<double>());
  }
  figure[count] = figure[list].size();
  figure["planned"] = planned;
  figure["strict"] = strict;
  figure["unreachable"] = unreachable;
  figure["median_seconds"] = seconds.empty() ? 0.0 : median(seconds);
}

// The figure over `starts`: one entry per start under `list`, the budgets, and count_entries's counts.
nlohmann::json starts_json(const NavigationTask& task, const std::vector<PlannedStart>& starts,
                           const PlanOptions& options, const std::string& count, const std::string& list) {
  nlohmann::json figure = {{"force_limit_N", options.force_limit_N},
                           {"budget_env_steps", options.max_env_steps},
                           {list, nlohmann::json::array()}};
  for (const PlannedStart& t : starts) figure[list].push_back(start_json(task, t));
  count_entries(figure, count, list);
  return figure;
}

}  // namespace

nlohmann::json row_planned(const NavigationTask& planning_task, int seeds, std::uint64_t first_seed,
                           const PlanOptions& options, const std::string& guide_actor, int threads) {
  std::map<std::string, PlannedStart> by_key;  // target_key order
  for (std::size_t a = 0; a < planning_task.anatomies.size(); ++a)
    for (std::size_t k = 0; k < planning_task.courses[a].size(); ++k) {
      PlannedStart t;
      t.anatomy = static_cast<int>(a);
      t.target = planning_task.courses[a][k].target_id;
      for (int s = 0; s < seeds; ++s) t.seeds.push_back(first_seed + static_cast<std::uint64_t>(s));
      by_key.emplace(target_key(planning_task.anatomies[a].name, t.target), t);
    }
  std::vector<PlannedStart> starts;
  for (auto& [key, t] : by_key) starts.push_back(t);
  plan_starts(planning_task, options, guide_actor, threads, starts);
  nlohmann::json j = starts_json(planning_task, starts, options, "targets", "per_target");
  j["seeds"] = seeds;
  return j;
}

nlohmann::json episodes_planned(const NavigationTask& planning_task, const std::vector<EpisodeRequest>& episodes,
                                const PlanOptions& options, const std::string& guide_actor, int threads) {
  std::vector<PlannedStart> starts;
  for (const EpisodeRequest& e : episodes) {
    PlannedStart t;
    t.anatomy = e.anatomy;
    t.target = e.target_id;
    t.seeds = {e.seed};
    starts.push_back(t);
  }
  plan_starts(planning_task, options, guide_actor, threads, starts);
  return starts_json(planning_task, starts, options, "episodes", "per_episode");
}

nlohmann::json join_episodes_planned(const std::vector<const nlohmann::json*>& parts) {
  if (parts.empty()) throw std::invalid_argument("join_episodes_planned: nothing to join");
  nlohmann::json joined = *parts[0];
  joined.erase("columns");
  joined["per_episode"] = nlohmann::json::array();
  for (const nlohmann::json* p : parts)
    for (const nlohmann::json& e : p->at("per_episode")) joined["per_episode"].push_back(e);
  count_entries(joined, "episodes", "per_episode");
  return joined;
}

nlohmann::json planned_against_columns(const nlohmann::json& planned, const nlohmann::json& results) {
  std::map<std::string, bool> plan_found;  // episode_key -> a plan from that start
  for (const nlohmann::json& e : planned.at("per_episode")) plan_found[episode_key(e)] = e["found"] != "none";
  nlohmann::json columns = nlohmann::json::object();
  for (const auto& [column, summary] : results.items()) {
    int episodes = 0, reached = 0, with_plan = 0, both = 0, plan_only = 0, reached_only = 0;
    for (const nlohmann::json& ep : summary.value("results", nlohmann::json::array())) {
      const auto it = plan_found.find(episode_key(ep));
      if (it == plan_found.end()) continue;
      const bool ok = ep["outcome"] == "success";
      ++episodes;
      reached += ok;
      with_plan += it->second;
      both += ok && it->second;
      plan_only += !ok && it->second;
      reached_only += ok && !it->second;
    }
    columns[column] = {{"episodes", episodes},         {"reached", reached},
                       {"planned", with_plan},         {"reached_and_planned", both},
                       {"planned_not_reached", plan_only}, {"reached_not_planned", reached_only}};
  }
  return columns;
}

}  // namespace gw
