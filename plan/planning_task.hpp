#pragma once
// planning_task_config: the task a procedure plan runs in (docs/planning.md).
// Input: the base task (navigate's: the defaults or a --task). Output: the same task with the act/2 action
// space (insertion in [-1, 1] and rotation at every control period), applied everywhere (control "always": a
// clinician's hand is on the wire the whole way), observation obs/8 (what the generalist push/pull actor
// sees, obs/5 and the tip's wall force; obs/5 is its first 14 entries: the plan's steps are demonstrations in an
// actor's layout), and the procedure going on after a wrong branch is
// entered (recovery_attempts kPlanEntries, recovery_time_s kPlanTimeS) so a plan may pull out and retry.
#include "task/task_config.hpp"

namespace gw {

inline constexpr int kPlanEntries = 1000;    // wrong-branch entries a procedure plan may pull out of
inline constexpr double kPlanTimeS = 600.0;  // simulated seconds past the strict step limit

TaskConfig planning_task_config(const TaskConfig& base);

}  // namespace gw
