#include "plan/lead_in.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gw {
namespace {

// How a lead-in step ended the controller's episode ("" when it goes on).
std::string ended_by(const StepOutcome& out, const EpisodeState& s, int bound) {
  if (out.info.success) return "success";
  if (!out.info.problem.empty()) return out.info.problem;
  if (s.procedure.attempts_used > kLeadInEntries) return "wrong branch";
  if (out.info.stuck) return "stuck";
  if (out.info.wire_exhausted) return "wire exhausted";
  if (out.terminated || out.truncated) return "step limit";
  if (s.steps >= bound) return "time";
  return "";
}

}  // namespace

LeadIn lead_in(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed, const PlanGuide& controller,
               int back_steps, double force_limit_N) {
  if (back_steps < 0) throw std::invalid_argument("lead_in: back_steps must be >= 0");
  LeadIn li;
  EpisodeState s = reset_episode(task, anatomy, target_id, seed);
  const EpisodeState start = s;
  const int bound = s.max_steps + static_cast<int>(std::lround(kLeadInTimeS / (task.config.frame_skip * task.config.dt_s)));
  double deepest = s.progress_mm;
  std::vector<Action> actions;
  std::vector<bool> in_control;
  double run_peak_tip_mN = 0.0, run_peak_node_mN = 0.0;
  if (controller.begin) controller.begin();
  while (li.outcome.empty()) {
    in_control.push_back(s.in_control);
    actions.push_back(controller.act(s.obs));
    const StepOutcome out = step_episode(task, s, actions.back());
    run_peak_tip_mN = std::max(run_peak_tip_mN, out.info.tip_force_mN);
    run_peak_node_mN = std::max(run_peak_node_mN, out.info.wall_force_peak_node_mN);
    if (s.progress_mm > deepest) {
      deepest = s.progress_mm;
      li.deepest_step = static_cast<int>(actions.size());
    }
    li.outcome = ended_by(out, s, bound);
  }
  li.ran = static_cast<int>(actions.size());
  if (li.outcome == "success" && run_peak_tip_mN <= 1000.0 * force_limit_N) {  // its own episode is the plan
    li.steps = li.ran;
    li.state = std::move(s);
    li.actions = std::move(actions);
    li.in_control = std::move(in_control);
    li.peak_tip_mN = run_peak_tip_mN;
    li.peak_node_mN = run_peak_node_mN;
    return li;
  }
  // The start: back_steps before the deepest step, and never the episode's last (its end is no state to go on from).
  li.steps = std::max(0, std::min(li.deepest_step, li.ran - 1) - back_steps);
  li.state = start;
  for (int k = 0; k < li.steps; ++k) {
    li.actions.push_back(actions[static_cast<std::size_t>(k)]);
    li.in_control.push_back(in_control[static_cast<std::size_t>(k)]);
    const StepOutcome out = step_episode(task, li.state, li.actions.back());
    li.peak_tip_mN = std::max(li.peak_tip_mN, out.info.tip_force_mN);
    li.peak_node_mN = std::max(li.peak_node_mN, out.info.wall_force_peak_node_mN);
  }
  return li;
}

}  // namespace gw
