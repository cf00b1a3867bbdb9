#include "lib/runner/task_options.hpp"

#include <fstream>
#include <stdexcept>

#include "task/action_layout.hpp"
#include "task/task_config_json.hpp"

namespace gw {

namespace {

using nlohmann::json;

// A flag that sets task-JSON key `key` (a "/"-separated path for a nested one) to what `convert` makes of its value.
template <class T, class Convert>
CLI::Option* task_flag(CLI::App& app, TaskOptions& o, const std::string& name, const std::string& key,
                       const std::string& help, Convert convert) {
  o.flag_keys.emplace_back(name, key.substr(key.rfind('/') + 1));
  return app
      .add_option_function<T>(
          name,
          [&o, key, convert](const T& value) {
            json patch;
            patch[json::json_pointer("/" + key)] = convert(value);
            o.flags.merge_patch(patch);  // nested keys merge: --junctions and --omega-plane both reach "observation"
          },
          help)
      ->group("Task");
}

template <class T>
CLI::Option* task_flag(CLI::App& app, TaskOptions& o, const std::string& name, const std::string& key,
                       const std::string& help) {
  return task_flag<T>(app, o, name, key, help, [](const T& v) { return v; });
}

CLI::Option* task_switch(CLI::App& app, TaskOptions& o, const std::string& name, const json& patch,
                         const std::string& help) {
  return app.add_flag_callback(name, [&o, patch] { o.flags.merge_patch(patch); }, help)->group("Task");
}

json read_task_json(const std::string& task) {
  const std::size_t first = task.find_first_not_of(" \t");
  const bool inline_json = first != std::string::npos && task[first] == '{';
  const std::string where = inline_json ? "--task" : "--task: " + task;
  try {
    if (inline_json) return json::parse(task);
    std::ifstream in(task);
    if (!in) throw std::invalid_argument(where + ": cannot read the file (give a task JSON file, docs/task_settings.md)");
    return json::parse(in);
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(where + ": not JSON (" + e.what() + ")");
  }
}

}  // namespace

void add_task_options(CLI::App& app, TaskOptions& o) {
  app.add_option("--task", o.task,
                 "task settings: a JSON file (or an inline JSON object) of TaskConfig fields, docs/task_settings.md; "
                 "the task flags below override it; default: the shipped actor's task")
      ->group("Task");
  task_flag<double>(app, o, "--push-speed", "push_mm_per_s",
                    "insertion speed at the proximal end, mm/s (the shipped actors were trained at 10)");
  task_flag<double>(app, o, "--intermediate-target", "intermediate_target_mm",
                    "trees: lambda is measured to a point this many mm past each bifurcation (0 = at the hand-over)");
  task_flag<std::string>(app, o, "--control", "control_mode",
                         "when the action applies: always, near_bifurcation, auto (always on a single bifurcation)");
  task_flag<std::string>(app, o, "--task-scale", "task_scale",
                         "the wrong-branch and control-zone lengths in millimetres (fixed: the paper's, set for "
                         "coronaries) or from the vessel's walls (vessel); auto = vessel for an inlet wider than 4 mm "
                         "in radius (docs/vessel_scale.md)");
  // The observation and action: navigate and evaluate take them from the actor (its obs_layout, action_layout).
  task_flag<std::string>(app, o, "--omega-plane", "observation",
                         "omega's plane: approach (obs/3) or correct_branch (the paper's, obs/1)",
                         [](const std::string& plane) {
                           return plane == "correct_branch" ? json{{"omega_plane", plane}, {"omega_side", false}}
                                                            : json{{"omega_plane", plane}};
                         });
  task_switch(app, o, "--omega-side", {{"observation", {{"omega_side", true}}}},
              "observe omega's sine too (obs/3, the default; task/observation.hpp)");
  task_switch(app, o, "--push-pull",
              {{"action", action_layout_name(ActionLayout::kRotationInsertion)},
               {"observation", {{"omega_side", true}, {"push_pull", true}}}},
              "the actor also sets the insertion speed: action [rotation, insertion] (act/2), observation obs/5 "
              "(docs/recovery.md)");
  task_flag<std::string>(app, o, "--junctions", "observation/junctions",
                         "how a junction's wrong branches enter omega: separate (the paper's, every table row), "
                         "combined (obs/4) or kway (obs/6); docs/junctions.md");
  task_flag<int>(app, o, "--recovery", "recovery_attempts",
                 "the procedure goes on after the strict end (a wrong branch, a stall): at most K pull-backs and "
                 "retries (docs/recovery.md; an act/2 actor pulls back itself); the outcome stays the strict "
                 "episode's, the procedure's is under \"recovery\"");
  task_switch(app, o, "--recovery-assist", {{"recovery_assist", true}},
              "with --recovery and an act/2 actor: the wrapper pulls the wire back on a stall, after stuck_steps env "
              "steps in a wrong child or standing still after the strict end (docs/recovery.md \"Assisted "
              "recovery\")");
  task_flag<double>(app, o, "--recovery-retract", "recovery_retract_mm",
                    "with --recovery: pull the tip back to this many mm before the centre of the bifurcation it was "
                    "lost at")
      ->check(CLI::Range(0.0, 200.0));
  task_flag<double>(app, o, "--recovery-turn", "recovery_turn_rad",
                    "with --recovery: pull-back k turns the proximal end by k times this many degrees",
                    [](double deg) {  // in long double, as navigate always converted it (EIGEN_PI)
                      return static_cast<double>(deg * 3.141592653589793238462643383279502884L / 180.0);
                    })
      ->check(CLI::Range(0.0, 360.0));
  task_flag<double>(app, o, "--recovery-pull-speed", "recovery_pull_mm_per_s", "with --recovery: the pull-back speed, mm/s");
  task_flag<double>(app, o, "--force-limit", "force_limit_N",
                    "withhold the forward push while the wire presses the wall harder than this many newtons at one "
                    "node (0 = off, the paper's task; docs/recovery.md \"Force limit\")");
}

TaskConfig resolve_task_config(const TaskOptions& o, const TaskConfig& base) {
  TaskConfig config = base;
  if (!o.task.empty()) {
    try {
      config = task_config_from_json(read_task_json(o.task), config, /*check=*/false);  // the flags may complete it
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      throw std::invalid_argument(what.rfind("--task", 0) == 0 ? what : "--task " + o.task + ": " + what);
    }
  }
  try {
    return task_config_from_json(o.flags, config);
  } catch (const std::invalid_argument& e) {
    std::string what = e.what();
    // The check names the field; a value given by a flag is named by its flag too (the last one that sets it).
    std::string flag;
    const std::string given = o.flags.dump();
    for (const auto& [name, key] : o.flag_keys)
      if (what.find(key) != std::string::npos && given.find("\"" + key + "\"") != std::string::npos) flag = name;
    if (!flag.empty()) what = flag + ": " + what;
    throw std::invalid_argument(o.task.empty() ? what : "--task " + o.task + " with the task flags: " + what);
  }
}

}  // namespace gw
