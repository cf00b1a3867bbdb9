#include "engine/task/episode.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "engine/sim/step.hpp"
#include "engine/task/bifurcation_omega.hpp"
#include "engine/task/reward.hpp"

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

bool near_a_bifurcation(const TaskConfig& c, const Course& course, const Eigen::Vector3d& tip) {
  for (const CourseBifurcation& b : course.bifurcations)
    if ((tip - b.centre).norm() <= c.control_radius_mm) return true;
  return false;
}

// Tip far enough along a wrong child and closer to it than to any part of the course. (Comparing
// with the whole course, not just the continuation past the bifurcation, matters where a wrong
// child bends back towards the access vessel, e.g. an S-shaped pattern.)
bool in_wrong_branch(const TaskConfig& c, const Anatomy& anatomy, const Course& course, const Eigen::Vector3d& tip,
                     double course_distance) {
  for (const CourseBifurcation& b : course.bifurcations) {
    for (int w : b.wrong_branches) {
      const PolylineProjection pw = project_onto_polyline(anatomy.branch_lines[static_cast<size_t>(w)], tip);
      if (pw.arc >= c.wrong_branch_depth_mm && pw.distance < course_distance) return true;
    }
  }
  return false;
}

// Observes the wire: fills state.obs (theta, lambda, omega, speed; action set by the caller),
// advances the goal and the progress bookkeeping. `first` = at reset (history = current values).
void observe(const NavigationTask& task, EpisodeState& s, bool first) {
  const TaskConfig& c = task.config;
  const Course& course = *s.course;
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
    const OmegaReading reading = bifurcation_omega(b, kappa, rest, c.junctions);
    omega = reading.omega;
    side = reading.side;
  }
  o[obs_index::kOmega] = omega;
  o[obs_index::kOmegaSide] = side;

  s.in_control = course.policy_always || near_a_bifurcation(c, course, tip);
}

// Drawn after every other reset draw, and only when enabled, so episodes without it are unchanged.
void draw_roll_disturbance(const TaskConfig& c, double advance_mm, SplitMix64& rng, EpisodeState& s) {
  if (c.roll_disturbance_probability <= 0 || rng.uniform() >= c.roll_disturbance_probability) return;
  const double angle = c.roll_disturbance_min_rad + (c.roll_disturbance_max_rad - c.roll_disturbance_min_rad) * rng.uniform();
  const double steps_to_end = s.course->line.length / advance_mm;
  s.disturbance_from_step = static_cast<int>(0.5 * steps_to_end * rng.uniform());
  s.disturbance_steps = std::max(1, static_cast<int>(std::lround(angle / (c.max_rotation_rad_per_s * env_dt(c)))));
  s.disturbance_sign = rng.uniform() < 0.5 ? -1.0 : 1.0;
}

double disturbance_rate(const TaskConfig& c, const EpisodeState& s) {
  const bool on = s.steps >= s.disturbance_from_step && s.steps < s.disturbance_from_step + s.disturbance_steps;
  return on ? s.disturbance_sign * c.max_rotation_rad_per_s : 0.0;
}

// TaskConfig::random_start_probability: drawn after every other reset draw, and only when enabled,
// so episodes without it are unchanged. Pushes without rotation (as the push-only stretch between two
// control zones does) until the tip is at the drawn arc, then observes afresh so lambda_0 starts there.
void draw_random_start(const NavigationTask& task, SplitMix64& rng, EpisodeState& s) {
  const TaskConfig& c = task.config;
  if (c.random_start_probability <= 0 || rng.uniform() >= c.random_start_probability) return;
  const Course& course = *s.course;
  const double first_centre = course.bifurcations.empty() ? course.line.length : course.bifurcations.front().arc;
  const double from = s.progress_mm;
  const double to = from + (first_centre - c.random_start_margin_mm - from) * rng.uniform();
  if (to <= from) return;
  const VesselScene* scene = task.anatomies[static_cast<size_t>(s.anatomy)].scene.get();
  const Control push{c.push_mm_per_s, 0.0};
  // A wire that buckles instead of advancing stops the pre-push (3x the steps a free wire needs).
  const int max_steps = static_cast<int>(std::ceil(3.0 * (to - from) / (env_dt(c) * c.push_mm_per_s))) + 10;
  for (int k = 0; k < max_steps && s.progress_mm < to; ++k) {
    for (int f = 0; f < c.frame_skip; ++f) {
      const StepReport report = step(task.wire, scene, push, s.wire);
      if (!report.ok)
        throw std::runtime_error("random start: physics diverged while pushing the wire to its start: " +
                                 report.problem);
    }
    observe(task, s, true);
  }
  s.pre_pushed_mm = s.progress_mm - from;
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
  draw_roll_disturbance(c, advance, rng, s);
  observe(task, s, true);
  draw_random_start(task, rng, s);
  s.obs[obs_index::kAction] = 0.0;
  s.best_progress_mm = s.progress_mm;
  return s;
}

StepInfo episode_info(const NavigationTask& task, const EpisodeState& s) {
  StepInfo info;
  info.in_control = s.in_control;
  info.step = s.steps;
  info.goal = s.goal;
  info.goals = s.course ? static_cast<int>(s.course->goal_arc.size()) : 0;
  info.lambda_mm = s.lambda_mm;
  info.tip_to_target_mm = s.course ? (s.tip - s.course->target).norm() : 0.0;
  info.progress_mm = s.progress_mm;
  info.inserted_mm = s.wire.inserted_length_mm;
  (void)task;
  return info;
}

StepOutcome step_episode(const NavigationTask& task, EpisodeState& s, double action, const StepLimits& limits) {
  if (!std::isfinite(action)) throw std::invalid_argument("action is not a finite number");
  if (s.done) throw std::logic_error("the episode is over; reset before stepping");
  if (!s.course) throw std::logic_error("episode was never reset");
  const TaskConfig& c = task.config;
  const Anatomy& anatomy = task.anatomies[static_cast<size_t>(s.anatomy)];
  const double applied = s.in_control ? std::clamp(action, -1.0, 1.0) : 0.0;
  const Control control{c.push_mm_per_s, applied * c.max_rotation_rad_per_s + disturbance_rate(c, s)};

  StepOutcome out;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < c.frame_skip; ++k) {
    const StepReport report = step(task.wire, anatomy.scene.get(), control, s.wire);
    out.info.contacts = report.contacts;
    if (!report.ok) {
      out.info.problem = "physics diverged: " + report.problem;
      break;
    }
    if (limits.wall_time_s > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > limits.wall_time_s) {
      out.info.time_limit = true;
      out.info.problem = "env step exceeded its time limit of " + std::to_string(limits.wall_time_s) + " s";
      break;
    }
  }
  ++s.steps;
  const int contacts = out.info.contacts;
  if (!out.info.problem.empty()) {
    // The wire state is not trustworthy: keep the last observation, end the episode (truncated:
    // not an outcome of the agent's behaviour).
    s.done = true;
    std::string problem = std::move(out.info.problem);
    const bool time_limit = out.info.time_limit;
    out.info = episode_info(task, s);
    out.info.problem = std::move(problem);
    out.info.time_limit = time_limit;
    out.info.contacts = contacts;
    out.obs = s.obs;
    out.truncated = true;
    return out;
  }

  observe(task, s, false);
  s.obs[obs_index::kAction] = applied;
  out.obs = s.obs;
  out.reward = navigation_reward(s.obs[obs_index::kOmega], s.obs[obs_index::kLambda], applied, c.reward);

  if (s.progress_mm > s.best_progress_mm + c.stuck_progress_mm) {
    s.best_progress_mm = s.progress_mm;
    s.best_progress_step = s.steps;
  }
  out.info = episode_info(task, s);
  out.info.contacts = contacts;
  out.info.success = out.info.tip_to_target_mm <= c.success_radius_mm;
  out.info.wrong_branch = !out.info.success && in_wrong_branch(c, anatomy, *s.course, s.tip, s.course_distance_mm);
  out.terminated = out.info.success || out.info.wrong_branch;
  if (!out.terminated) {
    out.info.step_limit = s.steps >= s.max_steps;
    out.info.stuck = s.steps - s.best_progress_step >= c.stuck_steps;
    out.info.wire_exhausted = s.wire.inserted_length_mm >= task.wire.params.length_mm - c.wire_reserve_mm;
    out.truncated = out.info.step_limit || out.info.stuck || out.info.wire_exhausted;
  }
  s.done = out.terminated || out.truncated;
  return out;
}

}  // namespace gw
