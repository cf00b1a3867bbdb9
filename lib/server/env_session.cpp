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

// A request line parsed: a JSON object, else a RequestError naming what is wrong with it.
json parse_request(const std::string& line) {
  json req;
  try {
    req = json::parse(line);
  } catch (const json::parse_error& e) {
    throw RequestError(std::string("malformed JSON: ") + e.what());
  }
  if (!req.is_object()) throw RequestError("request must be a JSON object with a \"cmd\" field");
  return req;
}

// The request's "cmd" string, else a RequestError.
std::string request_cmd(const json& req) {
  const auto cmd_it = req.find("cmd");
  if (cmd_it == req.end() || !cmd_it->is_string())
    throw RequestError("request has no string field \"cmd\" (spec, reset, step, close)");
  return cmd_it->get<std::string>();
}

// A reset's seed: the request's "seed", or the next of the session's stream when it has none (or null).
std::uint64_t reset_seed(const json& req, std::uint64_t& seed_stream) {
  std::uint64_t seed;
  const auto sit = req.find("seed");
  if (sit == req.end() || sit->is_null()) {
    seed = next_seed(seed_stream);
  } else if (sit->is_number_unsigned()) {
    seed = sit->get<std::uint64_t>();
  } else {
    throw RequestError("reset: \"seed\" must be a non-negative integer or null");
  }
  return seed;
}

// The anatomy (-1 = drawn) and target (0 = drawn) a reset asks for.
struct ResetChoice {
  int anatomy = -1, target = 0;
};

// A reset's "options" (absent or null: both drawn), checked against the task; else a RequestError.
ResetChoice reset_options(const NavigationTask& task, const json& req) {
  ResetChoice c;
  const auto oit = req.find("options");
  if (oit != req.end() && !oit->is_null()) {
    if (!oit->is_object()) throw RequestError("reset: \"options\" must be an object or null");
    for (const auto& [key, value] : oit->items()) {
      if (key == "anatomy") {
        if (value.is_string()) {
          c.anatomy = find_anatomy(task, value.get<std::string>());
          if (c.anatomy < 0) throw RequestError("reset: unknown anatomy '" + value.get<std::string>() + "'");
        } else if (value.is_number_integer()) {
          c.anatomy = value.get<int>();
          if (c.anatomy < 0 || c.anatomy >= static_cast<int>(task.anatomies.size()))
            throw RequestError("reset: anatomy index " + std::to_string(c.anatomy) + " out of range 0.." +
                               std::to_string(task.anatomies.size() - 1));
        } else if (!value.is_null()) {
          throw RequestError("reset: options.anatomy must be a name or an index");
        }
      } else if (key == "target") {
        if (value.is_number_integer()) {
          c.target = value.get<int>();
          if (c.target < 1) throw RequestError("reset: options.target must be >= 1");
        } else if (!value.is_null()) {
          throw RequestError("reset: options.target must be an integer id");
        }
      } else {
        throw RequestError("reset: unknown option '" + key + "' (known: anatomy, target)");
      }
    }
  }
  return c;
}

// A new episode into `state` (has_episode set); returns the reset reply: obs and info with the seed and start.
std::string reset_reply(const NavigationTask& task, EpisodeState& state, bool& has_episode, const ResetChoice& c,
                        std::uint64_t seed) {
  try {
    state = reset_episode(task, c.anatomy, c.target, seed);
  } catch (const std::invalid_argument& e) {
    throw RequestError(std::string("reset: ") + e.what());
  }
  has_episode = true;
  json info = info_json(task, state, episode_info(task, state));
  info["seed"] = seed;
  info["path_length_mm"] = state.course->line.length;
  info["max_steps"] = state.max_steps;
  info["start_rotation_rad"] = state.start_rotation_rad;
  info["start_tilt_rad"] = state.start_tilt_rad;
  return json{{"ok", true}, {"obs", observation_json(state.obs, task.config.observation.size())}, {"info", info}}.dump();
}

// A step's "action": as many finite numbers as the task's action layout (insertion 1 when it has none).
Action step_action(const NavigationTask& task, const json& req) {
  const std::size_t n = static_cast<std::size_t>(action_layout_size(task.config.action));
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
  return Action{values[0], values[1]};
}

// One step of the session's episode (refused without one, or after its end); returns the step reply.
std::string step_reply(const NavigationTask& task, EpisodeState& state, bool has_episode, const Action& a,
                       const SessionOptions& options) {
  if (!has_episode) throw RequestError("step: no episode; send reset first");
  if (state.done) throw RequestError("step: the episode is over; send reset");
  StepLimits limits;
  limits.wall_time_s = options.step_time_limit_s;
  const StepOutcome out = step_episode(task, state, a, limits);
  if (out.info.time_limit) throw RequestError("step: " + out.info.problem + "; the episode is over, send reset");
  return json{{"ok", true},
              {"obs", observation_json(out.obs, task.config.observation.size())},
              {"reward", out.reward},
              {"terminated", out.terminated},
              {"truncated", out.truncated},
              {"info", info_json(task, state, out.info)}}
      .dump();
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
                         {"targets", task.courses[a].size()},
                         {"wire_diameter_mm", wire_of(task, static_cast<int>(a)).params.diameter_mm}});
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
    const json req = parse_request(line);
    const std::string cmd = request_cmd(req);

    if (cmd == "spec") return spec_json(task_);
    if (cmd == "close") {
      close_connection = true;
      return json{{"ok", true}}.dump();
    }
    if (cmd == "reset") {
      const std::uint64_t seed = reset_seed(req, seed_stream_);
      return reset_reply(task_, state_, has_episode_, reset_options(task_, req), seed);
    }
    if (cmd == "step") return step_reply(task_, state_, has_episode_, step_action(task_, req), options_);
    throw RequestError("unknown cmd '" + cmd + "' (spec, reset, step, close)");
  } catch (const RequestError& e) {
    return error_reply(e.what());
  } catch (const std::exception& e) {
    return error_reply(std::string("internal error: ") + e.what());
  }
}

}  // namespace gw
