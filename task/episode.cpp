// step_episode (episode.hpp): one env step as a short list of named stages (episode_stages.hpp), with the procedure
// (procedure.hpp) above the strict episode.
#include "task/episode.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "task/episode_stages.hpp"
#include "task/procedure.hpp"

namespace gw {

namespace {

void check_step(const EpisodeState& s, const Action& action) {
  if (!std::isfinite(action.rotation)) throw std::invalid_argument("action is not a finite number");
  if (!std::isfinite(action.insertion)) throw std::invalid_argument("insertion action is not a finite number");
  if (s.done) throw std::logic_error("the episode is over; reset before stepping");
  if (!s.course) throw std::logic_error("episode was never reset");
}

// The wire state is not trustworthy after a diverged physics step (or one cut off by the wall-time limit): the last
// observation stays and the episode ends, truncated (not an outcome of the agent's behaviour).
StepOutcome diverged_step(const NavigationTask& task, EpisodeState& s, const PhysicsSummary& physics, bool retracting) {
  StepOutcome out;
  s.done = true;
  out.info = episode_info(task, s);
  out.info.problem = physics.problem;
  out.info.time_limit = physics.time_limit;
  fill_physics_info(out.info, physics, retracting);
  out.info.strict_end = !s.procedure.strict_over;
  s.procedure.strict_over = true;
  out.info.recovery_attempts = s.procedure.attempts_used;
  out.obs = s.obs;
  out.truncated = true;
  return out;
}

}  // namespace

StepOutcome step_episode(const NavigationTask& task, EpisodeState& s, double rotation, const StepLimits& limits) {
  return step_episode(task, s, Action{rotation, 1.0}, limits);
}

StepOutcome step_episode(const NavigationTask& task, EpisodeState& s, const Action& action, const StepLimits& limits) {
  check_step(s, action);
  const TaskConfig& c = task.config;
  StepCommand command = command_step(task, s, action);
  if (command.retracting) procedure_command(task, s, command);
  const PhysicsSummary physics = advance_physics(task, s, command.control, limits);
  ++s.steps;
  if (!physics.problem.empty()) return diverged_step(task, s, physics, command.retracting);
  observe_episode(task, s, false);
  s.obs[obs_index::kAction] = command.rotation;
  s.obs[obs_index::kInsertion] = command.control.push_mm_per_s / c.push_mm_per_s;
  s.obs[obs_index::kTipForce] = std::min(physics.peak.tip_mN / (1000.0 * kTipForceScaleN), kTipForceCap);
  if (command.retracting) return retraction_step(task, s, command, physics);

  track_progress(c, s);
  StepOutcome out;
  out.info = episode_info(task, s);
  fill_physics_info(out.info, physics, false);
  const int lost = check_arrival(task, s, out.info);
  const bool push_pull = c.action == ActionLayout::kRotationInsertion;
  const bool entered = push_pull && observe_wrong_branch(s, lost, out.info);
  out.reward = step_reward(task, s, command, lost >= 0) - force_cost(c, physics);
  const bool stall = stalled(c, s);
  check_strict_end(task, s, stall, out);
  continue_procedure(task, s, lost, entered, stall, out);
  out.info.recovery_attempts = s.procedure.attempts_used;
  s.done = out.terminated || out.truncated;
  out.obs = s.obs;
  return out;
}

}  // namespace gw
