#include "lib/runner/row_planned.hpp"

#include <algorithm>
#include <atomic>
#include <map>
#include <thread>

#include "base/util/median.hpp"
#include "lib/runner/controller_guides.hpp"
#include "lib/runner/evaluation_table.hpp"

namespace gw {
namespace {

struct PlannedTarget {
  int anatomy = 0, target = 0;
  std::uint64_t seed = 0;
  ProcedurePlan plan;
  std::string error;
};

void plan_target(const NavigationTask& task, int seeds, std::uint64_t first_seed, const PlanOptions& options,
                 const std::string& guide_actor, PlannedTarget& t) {
  try {
    PlanOptions o = options;  // guides of its own: a controller is not shared between threads
    if (!guide_actor.empty()) o.guides = controller_guides(guide_actor);
    for (int k = 0; k < seeds; ++k) {
      t.seed = first_seed + static_cast<std::uint64_t>(k);
      t.plan = plan_procedure(task, t.anatomy, t.target, t.seed, o);
      if (t.plan.kind != PlanKind::kNone) return;
    }
  } catch (const std::exception& e) {
    t.error = e.what();
  }
}

nlohmann::json target_json(const NavigationTask& task, const PlannedTarget& t) {
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

}  // namespace

nlohmann::json row_planned(const NavigationTask& planning_task, int seeds, std::uint64_t first_seed,
                           const PlanOptions& options, const std::string& guide_actor, int threads) {
  std::map<std::string, PlannedTarget> by_key;  // target_key order
  for (std::size_t a = 0; a < planning_task.anatomies.size(); ++a)
    for (std::size_t k = 0; k < planning_task.courses[a].size(); ++k) {
      PlannedTarget t;
      t.anatomy = static_cast<int>(a);
      t.target = planning_task.courses[a][k].target_id;
      by_key.emplace(target_key(planning_task.anatomies[a].name, t.target), t);
    }
  std::vector<PlannedTarget*> todo;
  for (auto& [key, t] : by_key) todo.push_back(&t);
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i; (i = next++) < todo.size();)
      plan_target(planning_task, seeds, first_seed, options, guide_actor, *todo[i]);
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < std::max(1, threads); ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  nlohmann::json per_target = nlohmann::json::array();
  int planned = 0, strict = 0, unreachable = 0;
  std::vector<double> seconds;
  for (const PlannedTarget* t : todo) {
    planned += t->plan.kind != PlanKind::kNone;
    strict += t->plan.kind == PlanKind::kStrict;
    unreachable += t->plan.narrow.has_value();
    seconds.push_back(t->plan.strict.seconds + t->plan.procedure.seconds);
    per_target.push_back(target_json(planning_task, *t));
  }
  return {{"targets", todo.size()},
          {"planned", planned},
          {"strict", strict},
          {"unreachable", unreachable},
          {"force_limit_N", options.force_limit_N},
          {"budget_env_steps", options.max_env_steps},
          {"seeds", seeds},
          {"median_seconds", seconds.empty() ? 0.0 : median(seconds)},
          {"per_target", per_target}};
}

}  // namespace gw
