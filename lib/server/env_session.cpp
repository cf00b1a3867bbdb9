#include "lib/server/env_session.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "engine/scene/wall_motion.hpp"
#include "task/task_config_json.hpp"

namespace gw {

using nlohmann::json;

namespace {

struct RequestError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The first `size` entries: the layout's (observation.hpp).
json observation_json(const Observation& o, int size) {
  json a = json::array();
  for (int i = 0; i < size; ++i) a.push_back(o[static_cast<size_t>(i)]);
  return a;
}

json info_json(const NavigationTask& task, const EpisodeState& s, const StepInfo& i) {
  json j = {{"anatomy", task.anatomies[static_cast<size_t>(s.anatomy)].name},
            {"target", s.target_id},
            {"in_control", i.in_control},
            {"success", i.success},
            {"wrong_branch", i.wrong_branch},
            {"step_limit", i.step_limit},
            {"stuck", i.stuck},
            {"wire_exhausted", i.wire_exhausted},
            {"step", i.step},
            {"goal", i.goal},
            {"goals", i.goals},
            {"lambda_mm", i.lambda_mm},
            {"tip_to_target_mm", i.tip_to_target_mm},
            {"progress_mm", i.progress_mm},
            {"inserted_mm", i.inserted_mm},
            {"contacts", i.contacts},
            {"wall_force_peak_node_mN", i.wall_force_peak_node_mN},
            {"wall_force_peak_total_mN", i.wall_force_peak_total_mN},
            {"tip_force_mN", i.tip_force_mN}};
  if (!i.problem.empty()) j["problem"] = i.problem;
  if (task.config.force_limit_N > 0) j["push_held_steps"] = i.push_held_steps;  // physics steps (docs/recovery.md)
  if (task.config.recovery_attempts > 0) {  // the procedure goes on past the strict end (docs/recovery.md)
    j["strict_end"] = i.strict_end;
    j["recovery_attempts"] = i.recovery_attempts;
  }
  return j;
}

// Replace invalid UTF-8 (an error message may quote the client's bytes) instead of throwing.
std::string error_reply(const std::string& message) {
  return json{{"ok", false}, {"error", message}}.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::uint64_t next_seed(std::uint64_t& stream) {
  std::uint64_t z = (stream += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

std::string spec_json(const NavigationTask& task) {
  Observation low, high;
  observation_bounds(task.config, low, high);
  const int size = task.config.observation.size();
  json names = json::array();
  for (int i = 0; i < size; ++i) names.push_back(observation_names()[static_cast<size_t>(i)]);
  json anatomies = json::array();
  for (size_t a = 0; a < task.anatomies.size(); ++a) {
    anatomies.push_back({{"name", task.anatomies[a].name},
                         {"index", a},
                         {"targets", task.courses[a].size()}});
    const auto& scene = task.anatomies[a].scene;  // a beating wall (--heart-rate): its rate
    if (scene && scene->motion) anatomies.back()["heart_rate_bpm"] = scene->motion->heart_rate_bpm;
  }
  const TaskConfig& c = task.config;
  const bool push_pull = c.action == ActionLayout::kRotationInsertion;
  const json action_space = push_pull ? json{{"shape", {2}}, {"low", {-1.0, -1.0}}, {"high", {1.0, 1.0}},
                                             {"names", {"rotation", "insertion"}}}
                                      : json{{"shape", {1}}, {"low", {-1.0}}, {"high", {1.0}}, {"names", {"rotation"}}};
  json j = {{"ok", true},
            {"protocol", kProtocolVersion},
            {"obs_layout", c.observation.name()},
            {"action_layout", action_layout_name(c.action)},
            {"observation_space",
             {{"shape", {size}}, {"low", observation_json(low, size)}, {"high", observation_json(high, size)},
              {"names", names}}},
            {"action_space", action_space},
            {"anatomies", anatomies},
            {"task", task_config_to_json(c)}};  // the whole task: a client may send it back as --task
  return j.dump();
}

EnvSession::EnvSession(const NavigationTask& task, SessionOptions options, std::uint64_t session_seed)
    : task_(task), options_(options), seed_stream_(session_seed) {}

std::string EnvSession::handle(const std::string& line, bool& close_connection) {
  close_connection = false;
  try {
    json req;
    try {
      req = json::parse(line);
    } catch (const json::parse_error& e) {
      throw RequestError(std::string("malformed JSON: ") + e.what());
    }
    if (!req.is_object()) throw RequestError("request must be a JSON object with a \"cmd\" field");
    const auto cmd_it = req.find("cmd");
    if (cmd_it == req.end() || !cmd_it->is_string())
      throw RequestError("request has no string field \"cmd\" (spec, reset, step, close)");
    const std::string cmd = cmd_it->get<std::string>();

    if (cmd == "spec") return spec_json(task_);
    if (cmd == "close") {
      close_connection = true;
      return json{{"ok", true}}.dump();
    }
    if (cmd == "reset") {
      std::uint64_t seed;
      const auto sit = req.find("seed");
      if (sit == req.end() || sit->is_null()) {
        seed = next_seed(seed_stream_);
      } else if (sit->is_number_unsigned()) {
        seed = sit->get<std::uint64_t>();
      } else {
        throw RequestError("reset: \"seed\" must be a non-negative integer or null");
      }
      int anatomy = -1, target = 0;
      const auto oit = req.find("options");
      if (oit != req.end() && !oit->is_null()) {
        if (!oit->is_object()) throw RequestError("reset: \"options\" must be an object or null");
        for (const auto& [key, value] : oit->items()) {
          if (key == "anatomy") {
            if (value.is_string()) {
              anatomy = find_anatomy(task_, value.get<std::string>());
              if (anatomy < 0) throw RequestError("reset: unknown anatomy '" + value.get<std::string>() + "'");
            } else if (value.is_number_integer()) {
              anatomy = value.get<int>();
              if (anatomy < 0 || anatomy >= static_cast<int>(task_.anatomies.size()))
                throw RequestError("reset: anatomy index " + std::to_string(anatomy) + " out of range 0.." +
                                   std::to_string(task_.anatomies.size() - 1));
            } else if (!value.is_null()) {
              throw RequestError("reset: options.anatomy must be a name or an index");
            }
          } else if (key == "target") {
            if (value.is_number_integer()) {
              target = value.get<int>();
              if (target < 1) throw RequestError("reset: options.target must be >= 1");
            } else if (!value.is_null()) {
              throw RequestError("reset: options.target must be an integer id");
            }
          } else {
            throw RequestError("reset: unknown option '" + key + "' (known: anatomy, target)");
          }
        }
      }
      try {
        state_ = reset_episode(task_, anatomy, target, seed);
      } catch (const std::invalid_argument& e) {
        throw RequestError(std::string("reset: ") + e.what());
      }
      has_episode_ = true;
      json info = info_json(task_, state_, episode_info(task_, state_));
      info["seed"] = seed;
      info["path_length_mm"] = state_.course->line.length;
      info["max_steps"] = state_.max_steps;
      info["start_rotation_rad"] = state_.start_rotation_rad;
      info["start_tilt_rad"] = state_.start_tilt_rad;
      return json{{"ok", true}, {"obs", observation_json(state_.obs, task_.config.observation.size())}, {"info", info}}.dump();
    }
    if (cmd == "step") {
      const std::size_t n = static_cast<std::size_t>(action_layout_size(task_.config.action));
      const std::string expected = n == 1 ? "1 number (rotation)" : "2 numbers (rotation, insertion)";
      const auto ait = req.find("action");
      if (ait == req.end() || !ait->is_array()) throw RequestError("step: \"action\" must be a list of " + expected);
      if (ait->size() != n)
        throw RequestError("step: action has " + std::to_string(ait->size()) + " values, expected " + expected);
      double values[2] = {0.0, 1.0};
      for (std::size_t i = 0; i < n; ++i) {
        const std::string which = "step: action[" + std::to_string(i) + "]";
        if (!(*ait)[i].is_number()) throw RequestError(which + " is not a number");
        values[i] = (*ait)[i].get<double>();
        if (!std::isfinite(values[i])) throw RequestError(which + " is not finite");
      }
      const Action a{values[0], values[1]};
      if (!has_episode_) throw RequestError("step: no episode; send reset first");
      if (state_.done) throw RequestError("step: the episode is over; send reset");
      StepLimits limits;
      limits.wall_time_s = options_.step_time_limit_s;
      const StepOutcome out = step_episode(task_, state_, a, limits);
      if (out.info.time_limit) throw RequestError("step: " + out.info.problem + "; the episode is over, send reset");
      return json{{"ok", true},
                  {"obs", observation_json(out.obs, task_.config.observation.size())},
                  {"reward", out.reward},
                  {"terminated", out.terminated},
                  {"truncated", out.truncated},
                  {"info", info_json(task_, state_, out.info)}}
          .dump();
    }
    throw RequestError("unknown cmd '" + cmd + "' (spec, reset, step, close)");
  } catch (const RequestError& e) {
    return error_reply(e.what());
  } catch (const std::exception& e) {
    return error_reply(std::string("internal error: ") + e.what());
  }
}

}  // namespace gw
