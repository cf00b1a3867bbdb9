#include "lib/report/trajectory.hpp"

#include <algorithm>
#include <stdexcept>

namespace gw {

const std::vector<std::string> kTraceOutcomes = {"success", "wrong_branch", "stuck", "timeout", "diverged"};

void check_trace(const EpisodeTrace& t, const std::string& what) {
  auto fail = [&](const std::string& problem) { throw std::invalid_argument(what + ": " + problem); };
  const std::size_t n = t.time_s.size();
  auto same = [&](std::size_t m, const char* name) {
    if (m != n)
      fail(std::string(name) + " has " + std::to_string(m) + " frames but time_s has " + std::to_string(n));
  };
  same(t.tip.size(), "tip");
  same(t.action.size(), "action");
  same(t.agent_in_control.size(), "agent_in_control");
  if (!t.observation.empty()) {
    same(t.observation.size(), "observation");
    for (const auto& o : t.observation)
      if (o.size() != t.observation_names.size())
        fail("an observation has " + std::to_string(o.size()) + " values but there are " +
             std::to_string(t.observation_names.size()) + " observation names");
  }
  if (!t.goal.empty()) same(t.goal.size(), "goal");
  if (!t.wall_force_peak_node_mN.empty()) same(t.wall_force_peak_node_mN.size(), "wall_force_peak_node_mN");
  if (!t.wall_force_peak_total_mN.empty()) same(t.wall_force_peak_total_mN.size(), "wall_force_peak_total_mN");
  if (!t.wall_force_mean_total_mN.empty()) same(t.wall_force_mean_total_mN.size(), "wall_force_mean_total_mN");
  if (!t.tip_force_mN.empty()) same(t.tip_force_mN.size(), "tip_force_mN");
  if (!t.retracting.empty()) same(t.retracting.size(), "retracting");
  if (!t.insertion.empty()) same(t.insertion.size(), "insertion");
  if (!t.push_held_s.empty()) same(t.push_held_s.size(), "push_held_s");
  if (t.strict_end_frame < -1 || (t.strict_end_frame >= 0 && static_cast<std::size_t>(t.strict_end_frame) >= n))
    fail("strict_end_frame " + std::to_string(t.strict_end_frame) + " is outside -1.." + std::to_string(n) + "-1");
  if (t.recovery_attempts_allowed < 0 || t.recovery_attempts_used < 0)
    fail("recovery attempts must be >= 0");
  if (t.recovery_attempts_allowed > 0 &&
      std::find(kTraceOutcomes.begin(), kTraceOutcomes.end(), t.recovery_outcome) == kTraceOutcomes.end())
    fail("recovery outcome '" + t.recovery_outcome + "' is not a trace outcome");
  if (std::find(kTraceOutcomes.begin(), kTraceOutcomes.end(), t.outcome) == kTraceOutcomes.end()) {
    std::string valid;
    for (const auto& o : kTraceOutcomes) valid += (valid.empty() ? "" : ", ") + o;
    fail("outcome '" + t.outcome + "' is not one of " + valid);
  }
  if (t.target_id < 0) fail("target_id must be >= 0, got " + std::to_string(t.target_id));
  if (!t.wire_shape_frame.empty()) {
    if (t.wire_shape_frame.size() != t.wire_shapes.size())
      fail("wire_shape_frame has " + std::to_string(t.wire_shape_frame.size()) + " entries but there are " +
           std::to_string(t.wire_shapes.size()) + " wire shapes");
    for (int f : t.wire_shape_frame)
      if (f < 0 || static_cast<std::size_t>(f) >= n)
        fail("wire_shape_frame " + std::to_string(f) + " is outside 0.." + std::to_string(n) + "-1");
  }
}

int strict_end(const EpisodeTrace& t) {
  if (t.strict_end_frame >= 0) return t.strict_end_frame;
  return t.time_s.empty() ? 0 : static_cast<int>(t.time_s.size()) - 1;
}

const std::string& procedure_outcome(const EpisodeTrace& t) {
  return t.recovery_attempts_allowed > 0 ? t.recovery_outcome : t.outcome;
}

const std::string& procedure_detail(const EpisodeTrace& t) {
  return t.recovery_attempts_allowed > 0 ? t.recovery_detail : t.detail;
}

}  // namespace gw
