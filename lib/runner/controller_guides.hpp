#pragma once
// controller_guides: the table's steering controllers as the procedure planner's guides (PlanGuide,
// plan/plan_procedure.hpp), so that a plan reaches at least what they reach from the same start: the shipped actor
// (`actor_path`), the scripted rule and the rule turning the other way. Each runs in the planning task (act/2,
// control everywhere) and pushes at +1 as in its own task.
#include <string>
#include <vector>

#include "plan/plan_procedure.hpp"

namespace gw {

std::vector<PlanGuide> controller_guides(const std::string& actor_path);

// actor_guide: one actor JSON as a PlanGuide (a plan's lead-in, PlanOptions::lead_in), named by its file; it reads the
// first entries of the planning task's observation that its layout has.
PlanGuide actor_guide(const std::string& actor_path);

}  // namespace gw
