#include "plan/planning_task.hpp"

#include "task/task_config_json.hpp"

namespace gw {

TaskConfig planning_task_config(const TaskConfig& base) {
  const nlohmann::json patch = {{"action", "guidewire-nav/act/2"},
                                {"observation", "guidewire-nav/obs/8"},
                                {"control_mode", "always"},
                                {"recovery_attempts", kPlanEntries},
                                {"recovery_assist", false},
                                {"recovery_time_s", kPlanTimeS}};
  return task_config_from_json(patch, base);
}

}  // namespace gw
