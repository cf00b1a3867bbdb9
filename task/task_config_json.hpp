#pragma once
// Task settings as JSON (docs/task_settings.md): the one surface every app, the server and the training side
// read and record. Keys are TaskConfig's field names; the observation layout and the reward sigmoid are
// objects with their own fields' names, the enums their names ("auto", "guidewire-nav/act/2", ...).
#include <nlohmann/json.hpp>

#include "task/task_config.hpp"

namespace gw {

// The schema name a task JSON may carry as "format" (task_config_to_json writes it).
inline constexpr const char* kTaskFormat = "guidewire-nav/task/1";

// Inputs: a TaskConfig. Outputs: every field under its name, with "format": kTaskFormat.
nlohmann::json task_config_to_json(const TaskConfig& config);

// Inputs: `settings`, a JSON object holding any subset of the keys task_config_to_json writes (the observation
// may also be a layout name, "guidewire-nav/obs/3"); `base`, the values of the keys it does not hold.
// Outputs: `base` with those keys set, checked by check_task_config unless `check` is false (a first layer that a
// second completes: --task, then the flags). Throws std::invalid_argument naming the key for an unknown key, a value
// of the wrong type, a non-finite number or an unknown name.
TaskConfig task_config_from_json(const nlohmann::json& settings, TaskConfig base = {}, bool check = true);

}  // namespace gw
