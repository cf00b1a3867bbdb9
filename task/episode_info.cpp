// episode_info (episode.hpp): the info fields the state alone gives.
#include "task/episode_stages.hpp"

namespace gw {

StepInfo episode_info(const NavigationTask& task, const EpisodeState& s) {
  StepInfo info;
  info.in_control = s.in_control;
  info.step = s.steps;
  info.goal = s.goal;
  info.goals = s.course ? static_cast<int>(s.course->goal_arc.size()) : 0;
  info.lambda_mm = s.lambda_mm;
  info.tip_to_target_mm = s.course ? (s.tip - current_course(s).target).norm() : 0.0;
  info.progress_mm = s.progress_mm;
  info.inserted_mm = s.wire.inserted_length_mm;
  (void)task;
  return info;
}

}  // namespace gw
