// Stage command_step (episode_stages.hpp): the action as the wire's proximal command.
#include <algorithm>

#include "task/episode_stages.hpp"

namespace gw {

StepCommand command_step(const NavigationTask& task, const EpisodeState& s, const Action& action) {
  const TaskConfig& c = task.config;
  StepCommand cmd;
  cmd.retracting = s.procedure.retracting;
  cmd.omega_before = s.obs[obs_index::kOmega];
  cmd.rotation = s.in_control && !s.procedure.retracting ? std::clamp(action.rotation, -1.0, 1.0) : 0.0;
  // act/2 in control: the actor's insertion, not pulling the wire out past its start insertion: a pull is cut to
  // the length left above it (the inserted length is a sum of steps, so it may sit a rounding error above it).
  const bool push_pull = c.action == ActionLayout::kRotationInsertion;
  cmd.insertion = push_pull && s.in_control ? std::clamp(action.insertion, -1.0, 1.0) : 1.0;
  if (cmd.insertion < 0) {
    const double room_mm = s.wire.inserted_length_mm - c.initial_insertion_mm;
    const double full_pull_mm = c.push_mm_per_s * env_dt(c);  // one env step at insertion -1
    cmd.insertion = room_mm <= 1e-9 ? 0.0 : std::max(cmd.insertion, -room_mm / full_pull_mm);
  }
  cmd.control = Control{cmd.insertion * c.push_mm_per_s, cmd.rotation * c.max_rotation_rad_per_s};
  return cmd;
}

}  // namespace gw
