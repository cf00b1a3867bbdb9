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
  // act/2 in control: the actor's insertion, not pulling the wire out past its start insertion.
  const bool push_pull = c.action == ActionLayout::kRotationInsertion;
  cmd.insertion = push_pull && s.in_control ? std::clamp(action.insertion, -1.0, 1.0) : 1.0;
  if (cmd.insertion < 0 && s.wire.inserted_length_mm <= c.initial_insertion_mm) cmd.insertion = 0.0;
  cmd.control = Control{cmd.insertion * c.push_mm_per_s, cmd.rotation * c.max_rotation_rad_per_s};
  return cmd;
}

}  // namespace gw
