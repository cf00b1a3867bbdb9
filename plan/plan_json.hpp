#pragma once
// A procedure plan as JSON (format "guidewire-nav/plan/1", docs/planning.md) and back.
// plan_to_json: Input: a plan. Output: {"format", "found": none|strict|procedure, "reached", "steps",
// "procedure_time_s", "wrong_entries", "peak_tip_force_N", "peak_node_force_N", "tip_end", "tip_to_target_mm",
// "actions": [[rotation, insertion], ...] (the in-control steps', the order a controller is asked),
// "search": {"strict": {...}, "procedure": {...}}, and with a lead-in "lead_in": {"controller", "steps" (the plan's first
// steps, the controller's), "deepest_step", "ran", "outcome"}}; the caller adds what the plan ran on (anatomy, target,
// seed, task, wire, heart).
// plan_actions_from_json: Input: such a document; `where` names it in errors. Output: its actions. Throws
// std::invalid_argument naming `where` and the problem for another format or a malformed action list.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plan/plan_procedure.hpp"

namespace gw {

inline constexpr const char* kPlanFormat = "guidewire-nav/plan/1";

nlohmann::json plan_to_json(const ProcedurePlan& plan);

std::vector<Action> plan_actions_from_json(const nlohmann::json& plan, const std::string& where);

}  // namespace gw
