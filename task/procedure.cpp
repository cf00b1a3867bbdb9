// The procedure above the strict episode (procedure.hpp): recovery's pull-backs, act/2's retries and the assist.
#include "task/procedure.hpp"

#include <algorithm>
#include <cmath>

#include "task/wrong_branch_entered.hpp"

namespace gw {

namespace {

// A folded tip (after the strict end): the distal tangent points back down the vessel (theta_1 below this; the
// threshold the runner's fold count uses, lib/runner/episode_batch.hpp).
constexpr double kFoldedTheta = -0.5;

// Where to pull back to from the tip's progress `at` along the course. After a wrong branch at bifurcation `lost`
// (>= 0): recovery_retract_mm before its centre. After a stall or a fold: that far before the tip, and before the
// centre of any bifurcation the tip is within its control radius of (along the course), so the controller re-aims
// for it from the edge of its control zone.
double retract_target(const TaskConfig& c, const Course& course, double at, int lost) {
  if (lost >= 0) return course.bifurcations[static_cast<size_t>(lost)].arc - c.recovery_retract_mm;
  double to = at - c.recovery_retract_mm;
  for (const CourseBifurcation& b : course.bifurcations)
    if (std::abs(at - b.arc) <= b.control_radius) to = std::min(to, b.arc - c.recovery_retract_mm);
  return to;
}

// Env steps that pull-back `attempt` (1-based) turns for: attempt * recovery_turn_rad at the full rotation rate (at
// least one step).
int recovery_turn_steps(const TaskConfig& c, int attempt) {
  return std::max(1, static_cast<int>(std::lround(attempt * c.recovery_turn_rad / (c.max_rotation_rad_per_s * env_dt(c)))));
}

// Starts pulling the wire back to retract_target (one attempt; `new_attempt` false: a pull-back for an attempt
// already counted, act/2's entry into the wrong child it is pulled out of).
void start_retraction(const NavigationTask& task, EpisodeState& s, int lost, bool new_attempt = true) {
  const TaskConfig& c = task.config;
  if (new_attempt) ++s.procedure.attempts_used;
  s.procedure.retracting = true;
  s.in_control = false;
  s.procedure.retract_to_mm = retract_target(c, current_course(s), s.progress_mm, lost);
  const double pull_per_step = env_dt(c) * c.recovery_pull_mm_per_s;
  // Twice the steps the distance needs (a wire that slides back slower than it is pulled), and 1 s more.
  s.procedure.retract_steps_left =
      static_cast<int>(std::ceil(2.0 * std::max(0.0, s.progress_mm - s.procedure.retract_to_mm) / pull_per_step)) +
      static_cast<int>(std::ceil(1.0 / env_dt(c)));
  s.procedure.turn_steps_left = c.recovery_turn_rad > 0 ? recovery_turn_steps(c, s.procedure.attempts_used) : 0;
}

// The tip is back upstream. The goal is the one the tip's progress is before (a tip in a wrong branch may have
// projected past the hand-over point), lambda_0 is measured afresh from here (as at a hand-over), and the stall
// test starts again.
void end_retraction(const NavigationTask& task, EpisodeState& s) {
  const TaskConfig& c = task.config;
  const Course& course = current_course(s);
  s.procedure.retracting = false;
  int goal = 0;
  const int last_goal = static_cast<int>(course.goal_arc.size()) - 1;
  while (goal < last_goal && s.progress_mm >= course.goal_arc[static_cast<size_t>(goal)]) ++goal;
  s.goal = goal;
  s.lambda_mm = std::max(0.0, course.lambda_arc[static_cast<size_t>(goal)] - s.progress_mm);
  s.lambda0_mm = std::max(s.lambda_mm, 1e-3);
  s.obs[obs_index::kLambda] = s.obs[obs_index::kLambdaPrev] = lambda_ratio(c, s);
  s.in_control = course.policy_always || near_a_bifurcation(course, s.tip);
  s.stall.best_progress_mm = s.progress_mm;
  s.stall.best_progress_step = s.steps;
  s.stall.inserted_at_best_mm = s.wire.inserted_length_mm + s.force.withheld_mm;  // act/2's stall test starts again too
  s.procedure.standstill_at_mm = s.stall.inserted_at_best_mm;                          // and the assist's standstill test
  s.procedure.standstill_since_step = s.steps;
}

// act/1: the wrapper's pull-back after a wrong branch, a stall or (once the strict episode is over) a folded tip,
// while attempts and time are left; a strict step limit only lets the procedure go on.
void continue_rotation_procedure(const NavigationTask& task, EpisodeState& s, int lost, StepOutcome& out) {
  const TaskConfig& c = task.config;
  const bool folded = s.procedure.strict_over && s.obs[obs_index::kTheta] < kFoldedTheta;
  const bool time_left = s.steps < s.procedure.max_steps;
  if ((out.info.wrong_branch || out.info.stuck || folded) && s.procedure.attempts_used < c.recovery_attempts &&
      time_left) {
    start_retraction(task, s, lost);
    out.info.in_control = false;
    out.terminated = out.truncated = false;
  } else if (!out.info.wrong_branch && !out.info.stuck) {
    out.info.step_limit = !time_left;
    out.truncated = !time_left;
  }
}

// act/2: the procedure goes on under the actor. An entry into a wrong child uses one of K retries and the one after
// the K-th ends it, as does a stall (wire pushed in without progress); recovery_time_s past the step limit bounds it.
// With recovery_assist the wrapper's pull-back answers a stall (one attempt), a tip that stays stuck_steps env steps
// in a wrong child (no new attempt) and, after the strict end, a standstill (one attempt).
void continue_push_pull_procedure(const NavigationTask& task, EpisodeState& s, int lost, bool entered, bool stall,
                                  StepOutcome& out) {
  const TaskConfig& c = task.config;
  const bool in_wrong_branch = lost >= 0;
  const bool time_left = s.steps < s.procedure.max_steps;
  bool failed = !time_left;
  if (entered) {
    if (s.procedure.attempts_used < c.recovery_attempts)
      ++s.procedure.attempts_used;
    else
      failed = true;
  }
  // A tip still in the child it entered earlier goes on, and so does the step that ended the strict episode
  // unless it ends the procedure too; on such a step the flags say why the strict episode ended (for the
  // strict columns). A stall ends the procedure (with recovery_assist and an attempt left: a pull-back).
  out.terminated = entered && failed;
  out.truncated = !out.terminated && (failed || stall);
  if (c.recovery_assist && !failed) {
    s.procedure.wrong_branch_steps = in_wrong_branch ? s.procedure.wrong_branch_steps + 1 : 0;
    const bool lingering = in_wrong_branch && s.procedure.wrong_branch_steps >= c.stuck_steps;
    const bool retry = stall && (in_wrong_branch || s.procedure.attempts_used < c.recovery_attempts);
    // A standstill: since the tip last progressed, the commands have kept the wire within stuck_progress_mm of
    // where it was for stuck_steps env steps (an actor at a fixed point of its own; pushing is the stall above).
    const double commanded_mm = s.wire.inserted_length_mm + s.force.withheld_mm;
    if (s.stall.best_progress_step > s.procedure.standstill_since_step ||
        std::abs(commanded_mm - s.procedure.standstill_at_mm) >= c.stuck_progress_mm) {
      s.procedure.standstill_at_mm = commanded_mm;
      s.procedure.standstill_since_step = s.steps;
    }
    const bool standstill = s.procedure.strict_over && !in_wrong_branch && s.steps - s.procedure.standstill_since_step >= c.stuck_steps &&
                            s.procedure.attempts_used < c.recovery_attempts;
    if (lingering || retry || standstill) {
      start_retraction(task, s, lost, !in_wrong_branch);
      s.procedure.wrong_branch_steps = 0;
      out.info.in_control = false;
      out.truncated = false;
    }
  }
  const bool strict_verdict = out.info.strict_end && !out.terminated && !out.truncated;
  out.info.wrong_branch = strict_verdict ? in_wrong_branch : out.terminated;
  out.info.stuck = stall;
  out.info.step_limit = strict_verdict ? s.steps >= s.max_steps : !time_left;
}

}  // namespace

void procedure_command(const NavigationTask& task, EpisodeState& s, StepCommand& command) {
  const TaskConfig& c = task.config;
  command.control.push_mm_per_s = -c.recovery_pull_mm_per_s;
  if (s.procedure.turn_steps_left > 0) {  // pull-back k turns by k * recovery_turn_rad at the full rotation rate
    const double turn = s.procedure.attempts_used * c.recovery_turn_rad;
    command.control.rotate_rad_per_s += turn / (recovery_turn_steps(c, s.procedure.attempts_used) * env_dt(c));
    --s.procedure.turn_steps_left;
  }
}

StepOutcome retraction_step(const NavigationTask& task, EpisodeState& s, const StepCommand& command,
                            const PhysicsSummary& physics) {
  const TaskConfig& c = task.config;
  StepOutcome out;
  if (c.action == ActionLayout::kRotationInsertion) {
    // recovery_assist: the flag follows the tip out of the wrong child; time and force still cost
    const Anatomy& anatomy = task.anatomies[static_cast<size_t>(s.anatomy)];
    const Anatomy& geometry = s.shape.valid ? s.shape.anatomy : anatomy;
    const int lost = wrong_branch_entered(c, geometry, current_course(s), s.tip, s.course_distance_mm);
    s.obs[obs_index::kWrongBranch] = lost >= 0 ? 1.0 : 0.0;
    out.reward = -c.reward_time_per_step - force_cost(c, physics);
  } else {
    out.reward = step_reward(task, s, command, false) - force_cost(c, physics);  // before the goal is reset below
  }
  --s.procedure.retract_steps_left;
  const double pull_per_step = env_dt(c) * c.recovery_pull_mm_per_s;
  if (s.progress_mm <= s.procedure.retract_to_mm || s.procedure.retract_steps_left <= 0 ||
      s.wire.inserted_length_mm <= c.initial_insertion_mm + pull_per_step)
    end_retraction(task, s);
  else
    s.in_control = false;
  out.obs = s.obs;
  out.info = episode_info(task, s);
  fill_physics_info(out.info, physics, true);
  out.info.recovery_attempts = s.procedure.attempts_used;
  out.info.step_limit = s.steps >= s.procedure.max_steps;
  out.truncated = out.info.step_limit;
  s.done = out.truncated;
  return out;
}

void continue_procedure(const NavigationTask& task, EpisodeState& s, int lost, bool entered, bool stall,
                        StepOutcome& out) {
  const TaskConfig& c = task.config;
  if (c.recovery_attempts <= 0 || out.info.success || out.info.wire_exhausted) return;
  if (c.action == ActionLayout::kRotationInsertion)
    continue_push_pull_procedure(task, s, lost, entered, stall, out);
  else
    continue_rotation_procedure(task, s, lost, out);
}

}  // namespace gw
