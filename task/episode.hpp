#pragma once
// One navigation episode (paper 2.2): reset places the wire at the inlet with a seeded random roll
// and tilt; each env step pushes at constant speed for frame_skip physics steps while rotating at
// action * max rotation rate, then observes, rewards and checks the end conditions.
// Like mjData, EpisodeState is plain mutable data: copy it to branch an episode. Deterministic:
// the same task, seed and actions give the same trajectory bit for bit.
#include <cstdint>
#include <string>

#include "task/action_layout.hpp"
#include "task/course_shape.hpp"
#include "task/navigation_task.hpp"
#include "task/observation.hpp"
#include "task/tip_samples.hpp"
#include "engine/wire/wire_state.hpp"

namespace gw {

// The stall tests' clock: when the tip last gained stuck_progress_mm along its course, and the insertion then.
struct StallClock {
  double best_progress_mm = 0.0;
  int best_progress_step = 0;
  double inserted_at_best_mm = 0.0;  // the commanded insertion (inserted + withheld) then (act/2's stall)
};

// act/2's reward pays only for going deeper than ever (RewardProgress): the insertion commands summed (full-speed
// env steps pushed, net) and their largest value so far; the tip's deepest projection on the course (mm).
struct PushPullDepth {
  double pushed_steps = 0.0;
  double deepest_pushed_steps = 0.0;
  double deepest_progress_mm = 0.0;
};

// Force limit (TaskConfig::force_limit_N > 0; else withheld_mm stays 0): the last physics step's largest
// single-node wall force, and how much further in the commands would have put the wire than the limit let it
// (mm; the commanded forward push and the backing off), which the stall tests count as pushed.
struct ForceLimitState {
  double last_peak_node_mN = 0.0;
  double withheld_mm = 0.0;
};

// The procedure above the strict episode (procedure.hpp; TaskConfig::recovery_attempts > 0, else these stay as
// they are here but strict_over).
struct ProcedureState {
  bool strict_over = false;        // the paper's strict episode has ended (StepInfo::strict_end was reported)
  bool retracting = false;         // pulling the wire back: no action is applied (in_control is false)
  int attempts_used = 0;           // pull-backs started (act/2: entries into a wrong child gone on from)
  double retract_to_mm = 0.0;      // pull back until progress_mm is at most this
  int retract_steps_left = 0;      // bound on one pull-back (a wire caught on the wall stops pulling)
  int turn_steps_left = 0;         // env steps of the recovery turn still to apply
  int max_steps = 0;               // step limit with recovery: max_steps + recovery_time_s; else max_steps
  int wrong_branch_steps = 0;      // act/2 with recovery_assist: env steps the tip has stayed in a wrong child
  // act/2 with recovery_assist, the standstill test: the commanded insertion (inserted + withheld) when the tip
  // last progressed or the wire last moved stuck_progress_mm, and that env step.
  double standstill_at_mm = 0.0;
  int standstill_since_step = 0;
};

struct EpisodeState {
  int anatomy = -1;
  int target_id = 0;
  std::uint64_t seed = 0;
  const Course* course = nullptr;  // into the task's courses
  double start_rotation_rad = 0.0;
  double start_tilt_rad = 0.0;
  WireState wire;
  Observation obs{};
  int goal = 0;                    // index into course->goal_arc
  double lambda0_mm = 1.0;         // lambda when the current goal became current
  double lambda_mm = 0.0;          // tip-to-goal distance along the centerline (to course->lambda_arc)
  double progress_mm = 0.0;        // arc length of the tip's projection on the course
  double course_distance_mm = 0.0; // distance from the tip to the course centerline
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  bool in_control = true;          // whether the next action is applied
  int steps = 0;
  int max_steps = 0;
  bool done = false;
  StallClock stall;
  PushPullDepth depth;
  ForceLimitState force;
  ProcedureState procedure;
  TipSamples samples;              // scratch, kept here so stepping does not allocate
  // Moving wall (issue 36): the course in the wall's shape at the last observation's time (wire.time),
  // which the observation, the control spheres and the end tests read (current_course). Arcs (progress_mm,
  // lambda, goal arcs) are then measured along the current centerline. Never set on a static wall.
  CourseShape shape;
};

// The course geometry the episode reads now: s.shape.course on a moving wall, else the task's *s.course.
inline const Course& current_course(const EpisodeState& s) { return s.shape.valid ? s.shape.course : *s.course; }

// Why an episode ended (or that it did not) and what the agent cannot see but a user wants to log.
struct StepInfo {
  bool in_control = true;          // whether the NEXT action will be applied (trees: within 20 mm)
  bool success = false;            // terminated: tip within success_radius_mm of the target
  bool wrong_branch = false;       // terminated: tip entered a wrong child
  bool step_limit = false;         // truncated
  bool stuck = false;              // truncated: no progress for stuck_steps
  bool wire_exhausted = false;     // truncated: the wire is (almost) fully inserted
  bool time_limit = false;         // truncated: the step ran past StepLimits::wall_time_s
  std::string problem;             // non-empty when physics diverged or the time limit hit
  int step = 0;
  int goal = 0, goals = 1;         // current goal index / number of goals
  double lambda_mm = 0.0;
  double tip_to_target_mm = 0.0;
  double progress_mm = 0.0;
  double inserted_mm = 0.0;
  int contacts = 0;                // last physics step's contact count
  // Wall force over this env step's physics steps (wall_force.hpp), mN: the largest single-node force,
  // the largest and the mean total over the nodes, the largest force on the distal kTipForceLengthMm.
  double wall_force_peak_node_mN = 0.0;
  double wall_force_peak_total_mN = 0.0;
  double wall_force_mean_total_mN = 0.0;
  double tip_force_mN = 0.0;
  int push_held_steps = 0;         // physics steps of this env step the force limit backed the wire off in
  // Recovery (TaskConfig::recovery_attempts). strict_end: the paper's strict episode ends at this step and
  // the flags above say why (with 0 attempts it is terminated || truncated; with recovery the episode may
  // go on). retracting: this step pulled the wire back. recovery_attempts: pull-backs started so far.
  bool strict_end = false;
  bool retracting = false;
  int recovery_attempts = 0;
};

struct StepOutcome {
  Observation obs{};
  double reward = 0.0;
  bool terminated = false;  // success or wrong branch (an MDP end)
  bool truncated = false;   // step limit, stuck, wire exhausted, physics problem, time limit
  StepInfo info;
};

// Optional per-call limits (the server uses them so a runaway step cannot hang a connection).
struct StepLimits {
  double wall_time_s = 0.0;  // 0 = none; checked after every physics step
};

// Starts an episode. `anatomy` < 0 and `target_id` == 0 mean "draw from the seed". Throws
// std::invalid_argument for an unknown anatomy index or target (naming the valid range).
EpisodeState reset_episode(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed);

// Info describing the current state (what reset reports).
StepInfo episode_info(const NavigationTask& task, const EpisodeState& state);

// One env step with `action` (each value clipped to [-1, 1]; ignored while !state.in_control, when the
// task pushes at +1 and does not turn). act/1 tasks read only the rotation and push at the constant speed;
// act/2 tasks (push/pull) also apply the insertion, never pulling the wire back past its start insertion.
// Throws std::invalid_argument for a non-finite value and std::logic_error when the episode is over.
StepOutcome step_episode(const NavigationTask& task, EpisodeState& state, const Action& action,
                         const StepLimits& limits = {});
// The paper's action: the rotation alone, pushing at the constant speed.
StepOutcome step_episode(const NavigationTask& task, EpisodeState& state, double rotation, const StepLimits& limits = {});

}  // namespace gw
