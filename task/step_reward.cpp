// Stage step_reward and force_cost (episode_stages.hpp): the env step's reward.
#include <algorithm>

#include "task/episode_stages.hpp"
#include "task/reward.hpp"
#include "task/wall_force.hpp"

namespace gw {

double force_cost(const TaskConfig& c, const PhysicsSummary& physics) {
  const double over_safe_N = std::max(0.0, 1e-3 * physics.peak.peak_node_mN - kRuptureForceN);
  return c.reward_force_per_N * over_safe_N;  // 0: the paper's reward
}

double step_reward(const NavigationTask& task, EpisodeState& s, const StepCommand& command, bool in_wrong_branch) {
  const TaskConfig& c = task.config;
  if (c.action != ActionLayout::kRotationInsertion)
    return navigation_reward(s.obs[obs_index::kOmega], s.obs[obs_index::kLambda], command.rotation, c.reward);
  // New depth: how far this step's command took the wire past its deepest so far, in full-speed steps (the
  // commands, not the measured insertion, so that the constant push gives exactly 1); or how far the tip went along
  // the course past its deepest so far, in full-speed steps of advance (RewardProgress, reward.hpp).
  s.depth.pushed_steps += command.insertion;
  const double commanded = std::clamp(s.depth.pushed_steps - s.depth.deepest_pushed_steps, 0.0, 1.0);
  s.depth.deepest_pushed_steps = std::max(s.depth.deepest_pushed_steps, s.depth.pushed_steps);
  const double along_course =
      std::clamp((s.progress_mm - s.depth.deepest_progress_mm) / (env_dt(c) * c.push_mm_per_s), 0.0, 1.0);
  s.depth.deepest_progress_mm = std::max(s.depth.deepest_progress_mm, s.progress_mm);
  const double new_depth = c.reward.progress == RewardProgress::kCourse ? along_course : commanded;
  return push_pull_reward(s.obs[obs_index::kOmega], command.omega_before, s.obs[obs_index::kLambda], command.rotation,
                          new_depth, in_wrong_branch, c.reward_wrong_branch, c.reward_time_per_step, c.reward);
}

}  // namespace gw
