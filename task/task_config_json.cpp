#include "task/task_config_json.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gw {

namespace {

using nlohmann::json;

// The plain-number and flag fields, in TaskConfig's order; the enums and the two nested types are written out below.
struct DoubleField {
  const char* key;
  double TaskConfig::*member;
};
struct IntField {
  const char* key;
  int TaskConfig::*member;
};
constexpr DoubleField kDoubles[] = {
    {"dt_s", &TaskConfig::dt_s},
    {"push_mm_per_s", &TaskConfig::push_mm_per_s},
    {"max_rotation_rad_per_s", &TaskConfig::max_rotation_rad_per_s},
    {"initial_insertion_mm", &TaskConfig::initial_insertion_mm},
    {"max_start_tilt_rad", &TaskConfig::max_start_tilt_rad},
    {"tip_sample_spacing_mm", &TaskConfig::tip_sample_spacing_mm},
    {"lookahead_mm", &TaskConfig::lookahead_mm},
    {"branch_direction_mm", &TaskConfig::branch_direction_mm},
    {"max_abs_speed_ratio", &TaskConfig::max_abs_speed_ratio},
    {"max_lambda_ratio", &TaskConfig::max_lambda_ratio},
    {"success_radius_mm", &TaskConfig::success_radius_mm},
    {"wrong_branch_depth_mm", &TaskConfig::wrong_branch_depth_mm},
    {"control_radius_mm", &TaskConfig::control_radius_mm},
    {"wide_vessel_radius_mm", &TaskConfig::wide_vessel_radius_mm},
    {"intermediate_target_mm", &TaskConfig::intermediate_target_mm},
    {"max_steps_path_factor", &TaskConfig::max_steps_path_factor},
    {"stuck_progress_mm", &TaskConfig::stuck_progress_mm},
    {"wire_reserve_mm", &TaskConfig::wire_reserve_mm},
    {"recovery_retract_mm", &TaskConfig::recovery_retract_mm},
    {"recovery_pull_mm_per_s", &TaskConfig::recovery_pull_mm_per_s},
    {"recovery_turn_rad", &TaskConfig::recovery_turn_rad},
    {"recovery_time_s", &TaskConfig::recovery_time_s},
    {"reward_wrong_branch", &TaskConfig::reward_wrong_branch},
    {"reward_time_per_step", &TaskConfig::reward_time_per_step},
    {"reward_force_per_N", &TaskConfig::reward_force_per_N},
    {"force_limit_N", &TaskConfig::force_limit_N},
    {"close_junction_diameters", &TaskConfig::close_junction_diameters},
};
constexpr IntField kInts[] = {
    {"frame_skip", &TaskConfig::frame_skip},
    {"max_steps", &TaskConfig::max_steps},
    {"stuck_steps", &TaskConfig::stuck_steps},
    {"recovery_attempts", &TaskConfig::recovery_attempts},
};

[[noreturn]] void refuse(const std::string& key, const std::string& problem) {
  throw std::invalid_argument("task settings: \"" + key + "\" " + problem);
}

double number(const json& v, const std::string& key) {
  if (!v.is_number()) refuse(key, "must be a number, got " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) refuse(key, "must be finite");
  return x;
}

int integer(const json& v, const std::string& key) {
  if (!v.is_number_integer()) refuse(key, "must be an integer, got " + v.dump());
  const auto x = v.get<long long>();
  if (x < -2147483647LL || x > 2147483647LL) refuse(key, "is out of range");
  return static_cast<int>(x);
}

bool flag(const json& v, const std::string& key) {
  if (!v.is_boolean()) refuse(key, "must be true or false, got " + v.dump());
  return v.get<bool>();
}

std::string text(const json& v, const std::string& key) {
  if (!v.is_string()) refuse(key, "must be a string, got " + v.dump());
  return v.get<std::string>();
}

// Calls parse(value) and names the key in what it throws.
template <class Parse>
auto named(const std::string& key, Parse parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    refuse(key, std::string(": ") + e.what());
  }
}

json observation_json(const ObservationLayout& o) {
  json j = {{"omega_plane", omega_plane_name(o.omega_plane)},
            {"omega_side", o.omega_side},
            {"junctions", junction_model_name(o.junctions)},
            {"push_pull", o.push_pull}};
  if (o.tip_force) j["tip_force"] = true;  // only when on: the task JSON of every other layout is as before obs/8
  return j;
}

ObservationLayout observation_from_json(const json& v, ObservationLayout o) {
  if (v.is_string()) return named("observation", [&] { return ObservationLayout::parse(v.get<std::string>()); });
  if (!v.is_object()) refuse("observation", "must be a layout name or an object, got " + v.dump());
  for (const auto& [key, value] : v.items()) {
    const std::string name = "observation." + key;
    if (key == "omega_plane") o.omega_plane = named(name, [&] { return parse_omega_plane(text(value, name)); });
    else if (key == "omega_side") o.omega_side = flag(value, name);
    else if (key == "junctions") o.junctions = named(name, [&] { return parse_junction_model(text(value, name)); });
    else if (key == "push_pull") o.push_pull = flag(value, name);
    else if (key == "tip_force") o.tip_force = flag(value, name);
    else refuse(name, "is not a task setting (observation has omega_plane, omega_side, junctions, push_pull, tip_force; "
                      "docs/task_settings.md)");
  }
  return o;
}

}  // namespace

json task_config_to_json(const TaskConfig& c) {
  json j = {{"format", kTaskFormat}};
  for (const DoubleField& f : kDoubles) j[f.key] = c.*f.member;
  for (const IntField& f : kInts) j[f.key] = c.*f.member;
  j["recovery_assist"] = c.recovery_assist;
  j["action"] = action_layout_name(c.action);
  j["observation"] = observation_json(c.observation);
  j["reward"] = {{"omega_centre", c.reward.omega_centre}, {"omega_slope", c.reward.omega_slope}};
  // only when not the default: the task JSON of every act/2 run before it is as it was
  if (c.reward.progress != RewardProgress::kCommanded) j["reward"]["progress"] = reward_progress_name(c.reward.progress);
  j["task_scale"] = task_scale_name(c.task_scale);
  j["control_mode"] = control_mode_name(c.control_mode);
  return j;
}

TaskConfig task_config_from_json(const json& settings, TaskConfig c, bool check) {
  if (!settings.is_object()) throw std::invalid_argument("task settings must be a JSON object, got " + settings.dump());
  for (const auto& [key, value] : settings.items()) {
    bool done = false;
    for (const DoubleField& f : kDoubles)
      if (key == f.key) c.*f.member = number(value, key), done = true;
    for (const IntField& f : kInts)
      if (key == f.key) c.*f.member = integer(value, key), done = true;
    if (done) continue;
    if (key == "format") {
      if (value != kTaskFormat) refuse(key, std::string("must be \"") + kTaskFormat + "\", got " + value.dump());
    } else if (key == "recovery_assist") {
      c.recovery_assist = flag(value, key);
    } else if (key == "action") {
      c.action = named(key, [&] { return parse_action_layout(text(value, key)); });
    } else if (key == "observation") {
      c.observation = observation_from_json(value, c.observation);
    } else if (key == "reward") {
      if (!value.is_object())
        refuse(key, "must be an object {\"omega_centre\", \"omega_slope\", \"progress\"}, got " + value.dump());
      for (const auto& [k, v] : value.items()) {
        const std::string name = "reward." + k;
        if (k == "omega_centre") c.reward.omega_centre = number(v, name);
        else if (k == "omega_slope") c.reward.omega_slope = number(v, name);
        else if (k == "progress") c.reward.progress = named(name, [&] { return parse_reward_progress(text(v, name)); });
        else refuse(name, "is not a task setting (reward has omega_centre, omega_slope, progress)");
      }
    } else if (key == "task_scale") {
      c.task_scale = named(key, [&] { return parse_task_scale(text(value, key)); });
    } else if (key == "control_mode") {
      c.control_mode = named(key, [&] { return parse_control_mode(text(value, key)); });
    } else {
      refuse(key, "is not a task setting (docs/task_settings.md lists them)");
    }
  }
  if (!check) return c;
  named("observation", [&] { return c.observation.name(); });  // a combination no layout has
  check_task_config(c);
  return c;
}

}  // namespace gw
