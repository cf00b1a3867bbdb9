#include "lib/report/trace_json.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "lib/report/atomic_write.hpp"

namespace gw {
namespace {

using nlohmann::json;

// JSON has no NaN/inf: write null, so Python's json and jq read the file.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json point(const Eigen::Vector3d& p) { return json::array({number(p.x()), number(p.y()), number(p.z())}); }

double read_number(const json& j) {
  if (j.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!j.is_number()) throw std::runtime_error("expected a number or null, got " + std::string(j.type_name()));
  return j.get<double>();
}

Eigen::Vector3d read_point(const json& j) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error("expected a point [x, y, z]");
  return {read_number(j[0]), read_number(j[1]), read_number(j[2])};
}

const json& field(const json& j, const char* key) {
  auto it = j.find(key);
  if (it == j.end()) throw std::runtime_error(std::string("missing field '") + key + "'");
  return *it;
}

const json& array_field(const json& j, const char* key) {
  const json& a = field(j, key);
  if (!a.is_array()) throw std::runtime_error(std::string("field '") + key + "' must be an array");
  return a;
}

}  // namespace

std::string trace_to_json(const EpisodeTrace& t, int indent) {
  check_trace(t);
  json frames;
  frames["time_s"] = json::array();
  frames["tip"] = json::array();
  frames["action"] = json::array();
  frames["agent_in_control"] = json::array();
  for (std::size_t i = 0; i < t.time_s.size(); ++i) {
    frames["time_s"].push_back(number(t.time_s[i]));
    frames["tip"].push_back(point(t.tip[i]));
    frames["action"].push_back(number(t.action[i]));
    frames["agent_in_control"].push_back(static_cast<bool>(t.agent_in_control[i]));
  }
  if (!t.observation.empty()) {
    frames["observation"] = json::array();
    for (const auto& o : t.observation) {
      json row = json::array();
      for (double v : o) row.push_back(number(v));
      frames["observation"].push_back(std::move(row));
    }
  }
  if (!t.goal.empty()) frames["goal"] = t.goal;
  auto per_frame = [&](const char* key, const std::vector<double>& v) {
    if (v.empty()) return;
    frames[key] = json::array();
    for (double x : v) frames[key].push_back(number(x));
  };
  per_frame("wall_force_peak_node_mN", t.wall_force_peak_node_mN);
  per_frame("wall_force_peak_total_mN", t.wall_force_peak_total_mN);
  per_frame("wall_force_mean_total_mN", t.wall_force_mean_total_mN);
  per_frame("tip_force_mN", t.tip_force_mN);
  per_frame("insertion", t.insertion);
  per_frame("push_held_s", t.push_held_s);
  if (!t.retracting.empty()) {
    frames["retracting"] = json::array();
    for (bool r : t.retracting) frames["retracting"].push_back(r);
  }
  json shapes = json::array();
  for (std::size_t s = 0; s < t.wire_shapes.size(); ++s) {
    json shape;
    if (t.wire_shape_frame.empty()) {
      shape["frame"] = nullptr;
      shape["time_s"] = nullptr;
    } else {
      const int f = t.wire_shape_frame[s];
      shape["frame"] = f;
      shape["time_s"] = number(t.time_s[static_cast<std::size_t>(f)]);
    }
    shape["points"] = json::array();
    for (const auto& p : t.wire_shapes[s]) shape["points"].push_back(point(p));
    shapes.push_back(std::move(shape));
  }
  json j;
  j["schema"] = kTrajectorySchema;
  j["units"] = {{"length", "mm"}, {"time", "s"}, {"force", "mN"}};
  j["anatomy"] = t.anatomy;
  j["controller"] = t.controller;
  j["target_id"] = t.target_id;
  j["seed"] = t.seed;
  j["outcome"] = t.outcome;
  j["detail"] = t.detail;
  if (!std::isnan(t.omega_at_loss)) j["omega_at_loss"] = t.omega_at_loss;
  j["num_frames"] = t.time_s.size();
  if (t.strict_end_frame >= 0) j["strict_end_frame"] = t.strict_end_frame;
  if (t.recovery_attempts_allowed > 0)
    j["recovery"] = {{"attempts_allowed", t.recovery_attempts_allowed},
                     {"attempts_used", t.recovery_attempts_used},
                     {"outcome", t.recovery_outcome},
                     {"detail", t.recovery_detail}};
  if (!t.observation_names.empty()) j["observation_names"] = t.observation_names;
  j["frames"] = std::move(frames);
  j["wire_shapes"] = std::move(shapes);
  // Replace invalid UTF-8 in free text (detail may quote a file name) instead of throwing.
  return j.dump(indent, ' ', false, json::error_handler_t::replace);
}

EpisodeTrace trace_from_json(const std::string& text, const std::string& origin) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(origin + ": not valid JSON (" + e.what() + ")");
  }
  EpisodeTrace t;
  try {
    if (!j.is_object()) throw std::runtime_error("top level must be an object");
    const std::string schema = field(j, "schema").get<std::string>();
    if (schema != kTrajectorySchema)
      throw std::runtime_error("schema is '" + schema + "', expected '" + kTrajectorySchema + "'");
    t.anatomy = field(j, "anatomy").get<std::string>();
    t.controller = field(j, "controller").get<std::string>();
    t.target_id = field(j, "target_id").get<int>();
    t.seed = field(j, "seed").get<std::uint64_t>();
    t.outcome = field(j, "outcome").get<std::string>();
    t.detail = field(j, "detail").get<std::string>();
    if (j.contains("omega_at_loss")) t.omega_at_loss = read_number(j["omega_at_loss"]);
    const json& frames = field(j, "frames");
    for (const auto& v : array_field(frames, "time_s")) t.time_s.push_back(read_number(v));
    for (const auto& v : array_field(frames, "tip")) t.tip.push_back(read_point(v));
    for (const auto& v : array_field(frames, "action")) t.action.push_back(read_number(v));
    for (const auto& v : array_field(frames, "agent_in_control")) t.agent_in_control.push_back(v.get<bool>());
    if (frames.contains("observation")) {
      t.observation_names = field(j, "observation_names").get<std::vector<std::string>>();
      for (const auto& row : array_field(frames, "observation")) {
        if (!row.is_array()) throw std::runtime_error("each observation must be an array");
        std::vector<double> o;
        for (const auto& v : row) o.push_back(read_number(v));
        t.observation.push_back(std::move(o));
      }
    }
    if (frames.contains("goal")) t.goal = array_field(frames, "goal").get<std::vector<int>>();
    auto read_per_frame = [&](const char* key, std::vector<double>& v) {
      if (frames.contains(key))
        for (const auto& x : array_field(frames, key)) v.push_back(read_number(x));
    };
    read_per_frame("wall_force_peak_node_mN", t.wall_force_peak_node_mN);
    read_per_frame("wall_force_peak_total_mN", t.wall_force_peak_total_mN);
    read_per_frame("wall_force_mean_total_mN", t.wall_force_mean_total_mN);
    read_per_frame("tip_force_mN", t.tip_force_mN);
    read_per_frame("insertion", t.insertion);
    read_per_frame("push_held_s", t.push_held_s);
    if (frames.contains("retracting"))
      for (const auto& v : array_field(frames, "retracting")) t.retracting.push_back(v.get<bool>());
    if (j.contains("strict_end_frame")) t.strict_end_frame = j["strict_end_frame"].get<int>();
    if (j.contains("recovery")) {
      const json& r = j["recovery"];
      t.recovery_attempts_allowed = field(r, "attempts_allowed").get<int>();
      t.recovery_attempts_used = field(r, "attempts_used").get<int>();
      t.recovery_outcome = field(r, "outcome").get<std::string>();
      t.recovery_detail = field(r, "detail").get<std::string>();
    }
    bool frames_known = true;
    for (const auto& shape : array_field(j, "wire_shapes")) {
      std::vector<Eigen::Vector3d> points;
      for (const auto& p : array_field(shape, "points")) points.push_back(read_point(p));
      t.wire_shapes.push_back(std::move(points));
      const json& f = field(shape, "frame");
      if (f.is_null()) frames_known = false;
      else t.wire_shape_frame.push_back(f.get<int>());
    }
    if (!frames_known) t.wire_shape_frame.clear();
    check_trace(t, "trace");
  } catch (const std::exception& e) {
    throw std::runtime_error(origin + ": " + e.what());
  }
  return t;
}

void write_trace_json(const EpisodeTrace& trace, const std::string& path) {
  check_trace(trace, path);
  write_file_atomic(path, trace_to_json(trace, 1) + "\n");
}

EpisodeTrace read_trace_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open for reading");
  std::ostringstream s;
  s << in.rdbuf();
  return trace_from_json(s.str(), path);
}

}  // namespace gw
