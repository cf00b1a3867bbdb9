#pragma once
// The task settings' command line, the same in navigate, evaluate and guidewire-server: `--task FILE.json`
// (or an inline JSON object) and one flag per commonly changed TaskConfig field, each written as its task-JSON
// key (task/task_config_json.hpp; docs/task_settings.md). gw-train sends its servers the same JSON.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "task/task_config.hpp"

namespace gw {

struct TaskOptions {
  std::string task;                                 // --task: a JSON file, or a JSON object given inline
  nlohmann::json flags = nlohmann::json::object();  // the task flags given, as task-JSON keys
  std::vector<std::pair<std::string, std::string>> flag_keys;  // each task flag and the key it sets (error messages)
};

// Inputs: an app, the options it fills. Outputs: --task and the task flags declared on `app` (group "Task").
void add_task_options(CLI::App& app, TaskOptions& options);

// Inputs: what add_task_options parsed; `base`, the settings before them. Outputs: base <- --task <- the flags,
// checked. Throws std::invalid_argument naming --task's file or the key for an unreadable file or a bad value.
TaskConfig resolve_task_config(const TaskOptions& options, const TaskConfig& base = {});

}  // namespace gw
