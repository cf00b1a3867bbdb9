#include "engine/task/episode.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "engine/sim/step.hpp"
#include "engine/task/bifurcation_omega.hpp"
#include "engine/task/reward.hpp"
#include "engine/task/wall_force.hpp"
#include "engine/task/wrong_branch_entered.hpp"

namespace gw {

namespace {

constexpr double kPi = 3.14159265358979323846;

// splitmix64: a tiny, portable generator, so episodes replay identically on every platform
// (std::uniform_real_distribution is implementation-defined).
struct SplitMix64 {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

double env_dt(const TaskConfig& c) { return c.frame_skip * c.dt_s; }

double lambda_ratio(const TaskConfig& c, const EpisodeState& s) {
  return std::clamp(s.lambda_mm / s.lambda0_mm, 0.0, c.max_lambda_ratio);
}

bool near_a_bifurcation(const Course& course, const Eigen::Vector3d& tip) {
  for (const CourseBifurcation& b : course.bifurcations)
    if ((tip - b.centre).norm() <= b.control_radius) return true;
  return false;
}

// Recovery: where to pull back to from the tip's progress `at` along the course. After a wrong branch
// at bifurcation `lost` (>= 0): recovery_retract_mm before its centre. After a stall or a fold: that far
// before the tip, and before the centre of any bifurcation the tip is within its control radius of (along
// the course), so the controller re-aims for it from the edge of its control zone.
double retract_target(const TaskConfig& c, const Course& course, double at, int lost) {
  if (lost >= 0) return course.bifurcations[static_cast<size_t>(lost)].arc - c.recovery_retract_mm;
  double to = at - c.recovery_retract_mm;
  for (const CourseBifurcation& b : course.bifurcations)
    if (std::abs(at - b.arc) <= b.control_radius) to = std::min(to, b.arc - c.recovery_retract_mm);
  return to;
}

// A folded tip (recovery only, after the strict end): the distal tangent points back down the vessel
// (theta_1 below this; the threshold the runner's fold count uses, apps/runner/episode_batch.hpp).
constexpr double kFoldedTheta = -0.5;

// Observes the wire: fills state.obs (theta, lambda, omega, speed; action set by the caller),
// advances the goal and the progress bookkeeping. `first` = at reset (history = current values).
void observe(const NavigationTask& task, EpisodeState& s, bool first) {
  const TaskConfig& c = task.config;
  const GraphMotion& motion = task.graph_motions[static_cast<size_t>(s.anatomy)];
  if (motion.points > 0)  // a moving wall: the course where the vessel is now (course_shape.hpp)
    course_shape_at(task.anatomies[static_cast<size_t>(s.anatomy)], motion, c, s.target_id, s.wire.time, s.shape);
  const Course& course = current_course(s);
  sample_tip(task.wire, s.wire, c.tip_sample_spacing_mm, s.samples);
  const Eigen::Vector3d tip = s.samples.position[0];

  Observation& o = s.obs;
  if (!first) {
    for (int i = 0; i < kThetaCount; ++i) o[obs_index::kThetaPrev + i] = o[obs_index::kTheta + i];
  }
  double tip_arc = 0.0;
  for (int i = 0; i < kThetaCount; ++i) {
    const PolylineProjection p = project_onto_polyline(course.line, s.samples.position[i]);
    if (i == 0) {
      tip_arc = p.arc;
      s.course_distance_mm = p.distance;
    }
    const Eigen::Vector3d ci = polyline_tangent(course.line, p.arc + c.lookahead_mm);
    o[obs_index::kTheta + i] = std::clamp(s.samples.tangent[i].dot(ci), -1.0, 1.0);
  }
  if (first) {
    for (int i = 0; i < kThetaCount; ++i) o[obs_index::kThetaPrev + i] = o[obs_index::kTheta + i];
  }

  // s = v . c over the last env step, in units of the push speed.
  const Eigen::Vector3d ct = polyline_tangent(course.line, tip_arc);
  const double speed = first ? 0.0 : (tip - s.tip).dot(ct) / (env_dt(c) * c.push_mm_per_s);
  o[obs_index::kSpeed] = std::clamp(speed, -c.max_abs_speed_ratio, c.max_abs_speed_ratio);
  s.tip = tip;
  s.progress_mm = tip_arc;

  // Goals: move to the next intermediate target once the tip is past the current one.
  const double previous_ratio = first ? 1.0 : lambda_ratio(c, s);
  bool goal_changed = first;
  const int last_goal = static_cast<int>(course.goal_arc.size()) - 1;
  while (s.goal < last_goal && tip_arc >= course.goal_arc[static_cast<size_t>(s.goal)]) {
    ++s.goal;
    goal_changed = true;
  }
  // act/2: a wire the actor pulls back behind a hand-over point gets that goal back (act/1 never pulls but
  // for recovery, whose end_retraction sets the goal).
  while (c.action == ActionLayout::kRotationInsertion && s.goal > 0 &&
         tip_arc < course.goal_arc[static_cast<size_t>(s.goal - 1)]) {
    --s.goal;
    goal_changed = true;
  }
  s.lambda_mm = std::max(0.0, course.lambda_arc[static_cast<size_t>(s.goal)] - tip_arc);
  if (goal_changed) s.lambda0_mm = std::max(s.lambda_mm, 1e-3);
  o[obs_index::kLambdaPrev] = goal_changed ? lambda_ratio(c, s) : previous_ratio;
  o[obs_index::kLambda] = lambda_ratio(c, s);

  // omega against the bifurcation of the current goal (none on a path without bifurcations).
  double omega = 0.0, side = 0.0;
  if (!course.bifurcations.empty()) {
    const size_t k = std::min(static_cast<size_t>(s.goal), course.bifurcations.size() - 1);
    const CourseBifurcation& b = course.bifurcations[k];
    const Eigen::Vector3d kappa = curvature_from_tangents(
        s.samples.tangent[0], s.samples.tangent[kTipSampleCount - 1], (kTipSampleCount - 1) * c.tip_sample_spacing_mm);
    const double rest = task.wire.params.tip_curvature_per_mm;
    const OmegaReading reading = bifurcation_omega(b, kappa, rest, c.observation.junctions);
    omega = reading.omega;
    side = reading.side;
  }
  o[obs_index::kOmega] = omega;
  o[obs_index::kOmegaSide] = side;

  s.in_control = course.policy_always || near_a_bifurcation(course, tip);
}

}  // namespace

EpisodeState reset_episode(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed) {
  const TaskConfig& c = task.config;
  SplitMix64 rng{seed};
  const int n_anatomies = static_cast<int>(task.anatomies.size());
  const int a = anatomy < 0 ? rng.below(n_anatomies) : anatomy;
  if (a >= n_anatomies)
    throw std::invalid_argument("anatomy index " + std::to_string(anatomy) + " does not exist; valid are 0.." +
                                std::to_string(n_anatomies - 1));
  const auto& courses = task.courses[static_cast<size_t>(a)];
  const int n_targets = static_cast<int>(courses.size());
  const int t = target_id == 0 ? 1 + rng.below(n_targets) : target_id;
  if (t < 1 || t > n_targets)
    throw std::invalid_argument("target " + std::to_string(target_id) + " does not exist in " +
                                task.anatomies[static_cast<size_t>(a)].name + "; valid targets are 1.." +
                                std::to_string(n_targets));
  EpisodeState s;
  s.anatomy = a;
  s.target_id = t;
  s.seed = seed;
  s.course = &courses[static_cast<size_t>(t - 1)];
  s.start_rotation_rad = 2.0 * kPi * rng.uniform();
  s.start_tilt_rad = c.max_start_tilt_rad * rng.uniform();
  const double azimuth = 2.0 * kPi * rng.uniform();

  const CenterlineGraph& g = task.anatomies[static_cast<size_t>(a)].graph;
  const Eigen::Vector3d d = g.inlet_direction.normalized();
  const Eigen::Vector3d e1 = d.unitOrthogonal();
  const Eigen::Vector3d e2 = d.cross(e1);
  const Eigen::Vector3d axis = std::cos(azimuth) * e1 + std::sin(azimuth) * e2;
  const Eigen::Vector3d direction = Eigen::AngleAxisd(s.start_tilt_rad, axis) * d;
  s.wire = make_initial_state(task.wire, g.inlet.position, direction, s.start_rotation_rad, c.initial_insertion_mm);

  const double advance = env_dt(c) * c.push_mm_per_s;
  s.max_steps = c.max_steps > 0 ? c.max_steps
                                : static_cast<int>(std::ceil(c.max_steps_path_factor * s.course->line.length / advance)) + 50;
  observe(task, s, true);
  s.obs[obs_index::kAction] = 0.0;
  s.obs[obs_index::kInsertion] = 1.0;
  s.obs[obs_index::kWrongBranch] = 0.0;
  s.best_progress_mm = s.progress_mm;
  s.inserted_at_best_mm = s.wire.inserted_length_mm;
  s.procedure_max_steps =
      s.max_steps + (c.recovery_attempts > 0 ? static_cast<int>(std::ceil(c.recovery_time_s / env_dt(c))) : 0);
  return s;
}

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

namespace {

// Recovery: env steps that pull-back `attempt` (1-based) turns for: attempt * recovery_turn_rad at the
// full rotation rate (at least one step).
int recovery_turn_steps(const TaskConfig& c, int attempt) {
  return std::max(1, static_cast<int>(std::lround(attempt * c.recovery_turn_rad / (c.max_rotation_rad_per_s * env_dt(c)))));
}

// Recovery: starts pulling the wire back to retract_target (one attempt; `new_attempt` false: a pull-back for
// an attempt already counted, act/2's entry into the wrong child it is pulled out of).
void start_retraction(const NavigationTask& task, EpisodeState& s, int lost, bool new_attempt = true) {
  const TaskConfig& c = task.config;
  if (new_attempt) ++s.recovery_attempts_used;
  s.retracting = true;
  s.in_control = false;
  s.retract_to_mm = retract_target(c, current_course(s), s.progress_mm, lost);
  const double pull_per_step = env_dt(c) * c.recovery_pull_mm_per_s;
  // Twice the steps the distance needs (a wire that slides back slower than it is pulled), and 1 s more.
  s.retract_steps_left =
      static_cast<int>(std::ceil(2.0 * std::max(0.0, s.progress_mm - s.retract_to_mm) / pull_per_step)) +
      static_cast<int>(std::ceil(1.0 / env_dt(c)));
  s.turn_steps_left = c.recovery_turn_rad > 0 ? recovery_turn_steps(c, s.recovery_attempts_used) : 0;
}

// Recovery: the tip is back upstream. The goal is the one the tip's progress is before (a tip in a wrong
// branch may have projected past the hand-over point), lambda_0 is measured afresh from here (as at a
// hand-over), and the stall test starts again.
void end_retraction(const NavigationTask& task, EpisodeState& s) {
  const TaskConfig& c = task.config;
  const Course& course = current_course(s);
  s.retracting = false;
  int goal = 0;
  const int last_goal = static_cast<int>(course.goal_arc.size()) - 1;
  while (goal < last_goal && s.progress_mm >= course.goal_arc[static_cast<size_t>(goal)]) ++goal;
  s.goal = goal;
  s.lambda_mm = std::max(0.0, course.lambda_arc[static_cast<size_t>(goal)] - s.progress_mm);
  s.lambda0_mm = std::max(s.lambda_mm, 1e-3);
  s.obs[obs_index::kLambda] = s.obs[obs_index::kLambdaPrev] = lambda_ratio(c, s);
  s.in_control = course.policy_always || near_a_bifurcation(course, s.tip);
  s.best_progress_mm = s.progress_mm;
  s.best_progress_step = s.steps;
  s.inserted_at_best_mm = s.wire.inserted_length_mm + s.withheld_mm;  // act/2's stall test starts again too
  s.standstill_at_mm = s.inserted_at_best_mm;                          // and the assist's standstill test
  s.standstill_since_step = s.steps;
}

// act/2 (push/pull): the end of step_episode once the tip's wrong-branch test (`lost`) is known; the caller
// takes the force cost off the reward. The strict end is the paper's (first wrong branch, a stall, the step
// limit); with recovery_attempts K > 0 the procedure goes on under the actor: an entry into a wrong child uses
// one of K retries and the one after the K-th ends it, as does a stall (wire pushed in without progress);
// recovery_time_s past the step limit bounds it (task_config.hpp). With recovery_assist the wrapper's pull-back
// answers a stall (one attempt), a tip that stays stuck_steps env steps in a wrong child (no new attempt) and,
// after the strict end, a standstill (one attempt).
void end_push_pull_step(const NavigationTask& task, EpisodeState& s, int lost, double rotation, double insertion,
                        double omega_before, StepOutcome& out) {
  const TaskConfig& c = task.config;
  const bool in_wrong_branch = lost >= 0;
  const bool entered = in_wrong_branch && s.obs[obs_index::kWrongBranch] == 0.0;  // the entry holds the last step's
  s.obs[obs_index::kWrongBranch] = in_wrong_branch ? 1.0 : 0.0;
  s.in_control = s.in_control || in_wrong_branch;  // an actor in a wrong child must be able to pull out
  out.info.in_control = s.in_control;
  out.obs = s.obs;
  // New depth: how far this step's command took the wire past its deepest so far, in full-speed steps (the
  // commands, not the measured insertion, so that the constant push gives exactly 1).
  s.pushed_steps += insertion;
  const double new_depth = std::clamp(s.pushed_steps - s.deepest_pushed_steps, 0.0, 1.0);
  s.deepest_pushed_steps = std::max(s.deepest_pushed_steps, s.pushed_steps);
  out.reward = push_pull_reward(s.obs[obs_index::kOmega], omega_before, s.obs[obs_index::kLambda], rotation, new_depth,
                                in_wrong_branch, c.reward_wrong_branch, c.reward_time_per_step, c.reward);

  // A stall is wire pushed in without progress: stuck_steps pushes at the full speed (the strict rule's 24 mm
  // under the constant push) since the tip last gained stuck_progress_mm. An actor that stops to aim does not
  // stall; one that keeps pushing a buckling wire, or pushes on along a wrong child, does.
  const double stall_mm = c.stuck_steps * env_dt(c) * c.push_mm_per_s;
  const bool stalled = s.wire.inserted_length_mm + s.withheld_mm - s.inserted_at_best_mm >= stall_mm;
  out.terminated = out.info.success || out.info.wrong_branch;
  if (!out.terminated) {
    out.info.step_limit = s.steps >= (s.strict_over ? s.procedure_max_steps : s.max_steps);
    out.info.stuck = stalled;
    out.info.wire_exhausted = s.wire.inserted_length_mm >= task.wire.params.length_mm - c.wire_reserve_mm;
    out.truncated = out.info.step_limit || out.info.stuck || out.info.wire_exhausted;
  }
  out.info.strict_end = !s.strict_over && (out.terminated || out.truncated);
  s.strict_over = s.strict_over || out.info.strict_end;
  if (c.recovery_attempts > 0 && !out.info.success && !out.info.wire_exhausted) {
    const bool time_left = s.steps < s.procedure_max_steps;
    bool failed = !time_left;
    if (entered) {
      if (s.recovery_attempts_used < c.recovery_attempts)
        ++s.recovery_attempts_used;
      else
        failed = true;
    }
    // A tip still in the child it entered earlier goes on, and so does the step that ended the strict episode
    // unless it ends the procedure too; on such a step the flags say why the strict episode ended (for the
    // strict columns). A stall ends the procedure (with recovery_assist and an attempt left: a pull-back).
    out.terminated = entered && failed;
    out.truncated = !out.terminated && (failed || stalled);
    if (c.recovery_assist && !failed) {
      s.wrong_branch_steps = in_wrong_branch ? s.wrong_branch_steps + 1 : 0;
      const bool lingering = in_wrong_branch && s.wrong_branch_steps >= c.stuck_steps;
      const bool retry = stalled && (in_wrong_branch || s.recovery_attempts_used < c.recovery_attempts);
      // A standstill: since the tip last progressed, the commands have kept the wire within stuck_progress_mm of
      // where it was for stuck_steps env steps (an actor at a fixed point of its own; pushing is the stall above).
      const double commanded_mm = s.wire.inserted_length_mm + s.withheld_mm;
      if (s.best_progress_step > s.standstill_since_step ||
          std::abs(commanded_mm - s.standstill_at_mm) >= c.stuck_progress_mm) {
        s.standstill_at_mm = commanded_mm;
        s.standstill_since_step = s.steps;
      }
      const bool standstill = s.strict_over && !in_wrong_branch && s.steps - s.standstill_since_step >= c.stuck_steps &&
                              s.recovery_attempts_used < c.recovery_attempts;
      if (lingering || retry || standstill) {
        start_retraction(task, s, lost, !in_wrong_branch);
        s.wrong_branch_steps = 0;
        out.info.in_control = false;
        out.truncated = false;
      }
    }
    const bool strict_verdict = out.info.strict_end && !out.terminated && !out.truncated;
    out.info.wrong_branch = strict_verdict ? in_wrong_branch : out.terminated;
    out.info.stuck = stalled;
    out.info.step_limit = strict_verdict ? s.steps >= s.max_steps : !time_left;
  }
  out.info.recovery_attempts = s.recovery_attempts_used;
  s.done = out.terminated || out.truncated;
}

}  // namespace

StepOutcome step_episode(const NavigationTask& task, EpisodeState& s, double rotation, const StepLimits& limits) {
  return step_episode(task, s, Action{rotation, 1.0}, limits);
}

StepOutcome step_episode(const NavigationTask& task, EpisodeState& s, const Action& action, const StepLimits& limits) {
  if (!std::isfinite(action.rotation)) throw std::invalid_argument("action is not a finite number");
  if (!std::isfinite(action.insertion)) throw std::invalid_argument("insertion action is not a finite number");
  if (s.done) throw std::logic_error("the episode is over; reset before stepping");
  if (!s.course) throw std::logic_error("episode was never reset");
  const TaskConfig& c = task.config;
  const Anatomy& anatomy = task.anatomies[static_cast<size_t>(s.anatomy)];
  const bool retracting = s.retracting;
  const bool push_pull = c.action == ActionLayout::kRotationInsertion;
  const double omega_before = s.obs[obs_index::kOmega];  // act/2's reward pays the aim by its change
  const double applied = s.in_control && !retracting ? std::clamp(action.rotation, -1.0, 1.0) : 0.0;
  // act/2 in control: the actor's insertion, not pulling the wire out past its start insertion.
  double insertion = push_pull && s.in_control ? std::clamp(action.insertion, -1.0, 1.0) : 1.0;
  if (insertion < 0 && s.wire.inserted_length_mm <= c.initial_insertion_mm) insertion = 0.0;
  Control control{insertion * c.push_mm_per_s, applied * c.max_rotation_rad_per_s};
  if (retracting) {
    control.push_mm_per_s = -c.recovery_pull_mm_per_s;
    if (s.turn_steps_left > 0) {  // pull-back k turns by k * recovery_turn_rad at the full rotation rate
      const double turn = s.recovery_attempts_used * c.recovery_turn_rad;
      control.rotate_rad_per_s += turn / (recovery_turn_steps(c, s.recovery_attempts_used) * env_dt(c));
      --s.turn_steps_left;
    }
  }

  StepOutcome out;
  WallForce peak;
  double total_sum = 0.0;
  int physics_steps = 0;
  int held = 0;
  const double limit_mN = 1e3 * c.force_limit_N;  // 0: off
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < c.frame_skip; ++k) {
    Control applied_control = control;
    if (limit_mN > 0 && s.last_peak_node_mN > limit_mN) {  // resistance: back off at the push speed
      const double back = s.wire.inserted_length_mm <= c.initial_insertion_mm ? 0.0 : -c.push_mm_per_s;
      if (control.push_mm_per_s > back) {  // not already pulling back as fast
        applied_control.push_mm_per_s = back;
        applied_control.rotate_rad_per_s = 0.0;
        s.withheld_mm += (std::max(control.push_mm_per_s, 0.0) - back) * c.dt_s;
        ++held;
      }
    }
    const StepReport report = step(task.wire, anatomy.scene.get(), applied_control, s.wire);
    out.info.contacts = report.contacts;
    if (!report.ok) {
      out.info.problem = "physics diverged: " + report.problem;
      break;
    }
    const WallForce f = wall_force(task.wire, s.wire);
    s.last_peak_node_mN = f.peak_node_mN;
    peak.peak_node_mN = std::max(peak.peak_node_mN, f.peak_node_mN);
    peak.total_mN = std::max(peak.total_mN, f.total_mN);
    peak.tip_mN = std::max(peak.tip_mN, f.tip_mN);
    total_sum += f.total_mN;
    ++physics_steps;
    if (limits.wall_time_s > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > limits.wall_time_s) {
      out.info.time_limit = true;
      out.info.problem = "env step exceeded its time limit of " + std::to_string(limits.wall_time_s) + " s";
      break;
    }
  }
  ++s.steps;
  const int contacts = out.info.contacts;
  auto fill_force = [&](StepInfo& info) {
    info.contacts = contacts;
    info.wall_force_peak_node_mN = peak.peak_node_mN;
    info.wall_force_peak_total_mN = peak.total_mN;
    info.wall_force_mean_total_mN = physics_steps > 0 ? total_sum / physics_steps : 0.0;
    info.tip_force_mN = peak.tip_mN;
    info.retracting = retracting;
    info.push_held_steps = held;
  };
  if (!out.info.problem.empty()) {
    // The wire state is not trustworthy: keep the last observation, end the episode (truncated:
    // not an outcome of the agent's behaviour).
    s.done = true;
    std::string problem = std::move(out.info.problem);
    const bool time_limit = out.info.time_limit;
    out.info = episode_info(task, s);
    out.info.problem = std::move(problem);
    out.info.time_limit = time_limit;
    fill_force(out.info);
    out.info.strict_end = !s.strict_over;
    s.strict_over = true;
    out.info.recovery_attempts = s.recovery_attempts_used;
    out.obs = s.obs;
    out.truncated = true;
    return out;
  }

  observe(task, s, false);
  s.obs[obs_index::kAction] = applied;
  s.obs[obs_index::kInsertion] = control.push_mm_per_s / c.push_mm_per_s;
  out.obs = s.obs;
  const double force_cost = c.reward_force_per_N * 1e-3 * peak.total_mN;  // 0: the paper's reward
  if (!push_pull)
    out.reward = navigation_reward(s.obs[obs_index::kOmega], s.obs[obs_index::kLambda], applied, c.reward) - force_cost;

  if (retracting) {
    // Recovery only: no end test but the procedure's step limit while the wire comes back.
    if (push_pull) {  // recovery_assist: the flag follows the tip out of the wrong child; time and force still cost
      const Anatomy& geometry = s.shape.valid ? s.shape.anatomy : anatomy;
      const int lost = wrong_branch_entered(c, geometry, current_course(s), s.tip, s.course_distance_mm);
      s.obs[obs_index::kWrongBranch] = lost >= 0 ? 1.0 : 0.0;
      out.reward = -c.reward_time_per_step - force_cost;
    }
    --s.retract_steps_left;
    const double pull_per_step = env_dt(c) * c.recovery_pull_mm_per_s;
    if (s.progress_mm <= s.retract_to_mm || s.retract_steps_left <= 0 ||
        s.wire.inserted_length_mm <= c.initial_insertion_mm + pull_per_step)
      end_retraction(task, s);
    else
      s.in_control = false;
    out.obs = s.obs;
    out.info = episode_info(task, s);
    fill_force(out.info);
    out.info.recovery_attempts = s.recovery_attempts_used;
    out.info.step_limit = s.steps >= s.procedure_max_steps;
    out.truncated = out.info.step_limit;
    s.done = out.truncated;
    return out;
  }

  if (s.progress_mm > s.best_progress_mm + c.stuck_progress_mm) {
    s.best_progress_mm = s.progress_mm;
    s.best_progress_step = s.steps;
    s.inserted_at_best_mm = s.wire.inserted_length_mm + s.withheld_mm;
  }
  out.info = episode_info(task, s);
  fill_force(out.info);
  out.info.success = out.info.tip_to_target_mm <= c.success_radius_mm;
  const Anatomy& geometry = s.shape.valid ? s.shape.anatomy : anatomy;  // the moving wall's, at this time
  const int lost = out.info.success ? -1 : wrong_branch_entered(c, geometry, current_course(s), s.tip, s.course_distance_mm);
  out.info.wrong_branch = lost >= 0;
  if (push_pull) {
    end_push_pull_step(task, s, lost, applied, insertion, omega_before, out);
    out.reward -= force_cost;
    return out;
  }
  out.terminated = out.info.success || out.info.wrong_branch;
  if (!out.terminated) {
    out.info.step_limit = s.steps >= (s.strict_over ? s.procedure_max_steps : s.max_steps);
    out.info.stuck = s.steps - s.best_progress_step >= c.stuck_steps;
    out.info.wire_exhausted = s.wire.inserted_length_mm >= task.wire.params.length_mm - c.wire_reserve_mm;
    out.truncated = out.info.step_limit || out.info.stuck || out.info.wire_exhausted;
  }
  out.info.strict_end = !s.strict_over && (out.terminated || out.truncated);
  s.strict_over = s.strict_over || out.info.strict_end;
  if (c.recovery_attempts > 0 && !out.info.success && !out.info.wire_exhausted) {
    // Recovery: a wrong branch, a stall or (once the strict episode is over) a folded tip starts a
    // pull-back while attempts and time are left; a strict step limit only lets the procedure go on.
    const bool folded = s.strict_over && s.obs[obs_index::kTheta] < kFoldedTheta;
    const bool time_left = s.steps < s.procedure_max_steps;
    if ((out.info.wrong_branch || out.info.stuck || folded) && s.recovery_attempts_used < c.recovery_attempts &&
        time_left) {
      start_retraction(task, s, lost);
      out.info.in_control = false;
      out.terminated = out.truncated = false;
    } else if (!out.info.wrong_branch && !out.info.stuck) {
      out.info.step_limit = !time_left;
      out.truncated = !time_left;
    }
  }
  out.info.recovery_attempts = s.recovery_attempts_used;
  s.done = out.terminated || out.truncated;
  return out;
}

}  // namespace gw
