#include "plan/plan_json.hpp"

#include <cmath>
#include <stdexcept>

namespace gw {
namespace {

nlohmann::json stats_json(const SearchStats& s) {
  return {{"env_steps", s.env_steps},
          {"maneuvers", s.maneuvers},
          {"generated", s.generated},
          {"over_force", s.over_force},
          {"ended", s.ended},
          {"wrong_branch", s.wrong_branch},
          {"found", s.found},
          {"guided", s.guided},
          {"nearest_target_mm", s.nearest_target_mm},
          {"best_tip", {s.best_tip.x(), s.best_tip.y(), s.best_tip.z()}},
          {"seconds", s.seconds},
          {"exhausted", s.exhausted}};
}

}  // namespace

nlohmann::json plan_to_json(const ProcedurePlan& plan) {
  nlohmann::json actions = nlohmann::json::array();
  for (std::size_t k = 0; k < plan.actions.size(); ++k)
    if (plan.in_control[k]) actions.push_back({plan.actions[k].rotation, plan.actions[k].insertion});
  nlohmann::json j = {{"format", kPlanFormat},
                      {"found", plan_kind_name(plan.kind)},
                      {"reached", plan.kind != PlanKind::kNone},
                      {"steps", plan.steps},
                      {"procedure_time_s", plan.time_s},
                      {"wrong_entries", plan.wrong_entries},
                      {"peak_tip_force_N", plan.peak_tip_force_N},
                      {"peak_node_force_N", plan.peak_node_force_N},
                      {"tip_end", {plan.tip_end.x(), plan.tip_end.y(), plan.tip_end.z()}},
                      {"tip_to_target_mm", plan.tip_to_target_mm},
                      {"actions", actions}};
  if (plan.kind == PlanKind::kNone) j["why"] = plan.why;
  if (!plan.guide.empty()) j["guide"] = plan.guide;
  if (plan.lead_in)
    j["lead_in"] = {{"controller", plan.lead_in->controller}, {"steps", plan.lead_in->steps},
                    {"deepest_step", plan.lead_in->deepest_step}, {"ran", plan.lead_in->ran},
                    {"outcome", plan.lead_in->outcome}};
  j["search"]["strict"] = stats_json(plan.strict);
  if (plan.procedure.maneuvers > 0) j["search"]["procedure"] = stats_json(plan.procedure);
  return j;
}

std::vector<Action> plan_actions_from_json(const nlohmann::json& plan, const std::string& where) {
  if (!plan.is_object() || plan.value("format", std::string()) != kPlanFormat)
    throw std::invalid_argument(where + ": not a plan (expected \"format\": \"" + std::string(kPlanFormat) +
                                "\"; `plan --out DIR` writes DIR/plan.json)");
  if (!plan.contains("actions") || !plan["actions"].is_array())
    throw std::invalid_argument(where + ": the plan has no \"actions\" list");
  std::vector<Action> out;
  for (const auto& a : plan["actions"]) {
    if (!a.is_array() || a.size() != 2 || !a[0].is_number() || !a[1].is_number())
      throw std::invalid_argument(where + ": action " + std::to_string(out.size()) +
                                  " is not [rotation, insertion]: " + a.dump());
    const Action action{a[0].get<double>(), a[1].get<double>()};
    if (!std::isfinite(action.rotation) || !std::isfinite(action.insertion) || std::abs(action.rotation) > 1 ||
        std::abs(action.insertion) > 1)
      throw std::invalid_argument(where + ": action " + std::to_string(out.size()) + " is outside [-1, 1]: " + a.dump());
    out.push_back(action);
  }
  return out;
}

}  // namespace gw
