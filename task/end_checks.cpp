// Stages track_progress, check_arrival, check_strict_end and their helpers (episode_stages.hpp): how far the tip
// got, whether it arrived or went wrong, and whether the paper's strict episode ends here.
#include "task/episode_stages.hpp"
#include "task/wrong_branch_entered.hpp"

namespace gw {

void track_progress(const TaskConfig& c, EpisodeState& s) {
  if (s.progress_mm > s.stall.best_progress_mm + c.stuck_progress_mm) {
    s.stall.best_progress_mm = s.progress_mm;
    s.stall.best_progress_step = s.steps;
    s.stall.inserted_at_best_mm = s.wire.inserted_length_mm + s.force.withheld_mm;
  }
}

bool stalled(const TaskConfig& c, const EpisodeState& s) {
  if (c.action != ActionLayout::kRotationInsertion) return s.steps - s.stall.best_progress_step >= c.stuck_steps;
  // act/2: stuck_steps pushes at the full speed (the strict rule's 24 mm under the constant push) since the tip last
  // gained stuck_progress_mm. An actor that stops to aim does not stall; one that keeps pushing a buckling wire, or
  // pushes on along a wrong child, does.
  const double stall_mm = c.stuck_steps * env_dt(c) * c.push_mm_per_s;
  return s.wire.inserted_length_mm + s.force.withheld_mm - s.stall.inserted_at_best_mm >= stall_mm;
}

void fill_physics_info(StepInfo& info, const PhysicsSummary& physics, bool retracting) {
  info.contacts = physics.contacts;
  info.wall_force_peak_node_mN = physics.peak.peak_node_mN;
  info.wall_force_peak_total_mN = physics.peak.total_mN;
  info.wall_force_mean_total_mN = physics.steps > 0 ? physics.total_sum_mN / physics.steps : 0.0;
  info.tip_force_mN = physics.peak.tip_mN;
  info.retracting = retracting;
  info.push_held_steps = physics.held;
}

int check_arrival(const NavigationTask& task, const EpisodeState& s, StepInfo& info) {
  const Anatomy& anatomy = task.anatomies[static_cast<size_t>(s.anatomy)];
  info.success = info.tip_to_target_mm <= task.config.success_radius_mm;
  const Anatomy& geometry = s.shape.valid ? s.shape.anatomy : anatomy;  // the moving wall's, at this time
  const int lost =
      info.success ? -1 : wrong_branch_entered(task.config, geometry, current_course(s), s.tip, s.course_distance_mm);
  info.wrong_branch = lost >= 0;
  return lost;
}

bool observe_wrong_branch(EpisodeState& s, int lost, StepInfo& info) {
  const bool in_wrong_branch = lost >= 0;
  const bool entered = in_wrong_branch && s.obs[obs_index::kWrongBranch] == 0.0;  // the entry holds the last step's
  s.obs[obs_index::kWrongBranch] = in_wrong_branch ? 1.0 : 0.0;
  s.in_control = s.in_control || in_wrong_branch;
  info.in_control = s.in_control;
  return entered;
}

void check_strict_end(const NavigationTask& task, EpisodeState& s, bool stall, StepOutcome& out) {
  const TaskConfig& c = task.config;
  out.terminated = out.info.success || out.info.wrong_branch;
  if (!out.terminated) {
    out.info.step_limit = s.steps >= (s.procedure.strict_over ? s.procedure.max_steps : s.max_steps);
    out.info.stuck = stall;
    out.info.wire_exhausted = s.wire.inserted_length_mm >= wire_of(task, s.anatomy).params.length_mm - c.wire_reserve_mm;
    out.truncated = out.info.step_limit || out.info.stuck || out.info.wire_exhausted;
  }
  out.info.strict_end = !s.procedure.strict_over && (out.terminated || out.truncated);
  s.procedure.strict_over = s.procedure.strict_over || out.info.strict_end;
}

}  // namespace gw
