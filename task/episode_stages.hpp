#pragma once
// The stages of one env step (step_episode, episode.cpp), as MuJoCo's mj_step lists its own:
//   command_step      the action as the wire's proximal command (procedure_command: the pull-back's instead)
//   advance_physics   frame_skip physics steps under the force limit, with the step's wall-force figures
//   observe_episode   the observation, the goal and the progress along the course
//   track_progress    the stall clocks
//   check_arrival     success and the wrong-branch test
//   step_reward       paper Eq. 3 (act/1) or the push/pull reward (act/2), less the force cost
//   check_strict_end  the paper's strict end: success, wrong branch, step limit, stall, wire exhausted
// and, above the strict episode, the procedure (procedure.hpp): recovery's pull-backs and the assist.
// Internal to task: the types and functions here are the episode's parts, not an interface.
#include <algorithm>
#include <string>

#include "engine/sim/step.hpp"
#include "task/episode.hpp"
#include "task/wall_force.hpp"

namespace gw {

// One env step's command, and what the observation reports of it.
struct StepCommand {
  Control control;            // proximal push speed and rotation rate for every physics step of the env step
  double rotation = 0.0;      // the rotation action applied, in [-1, 1] (0 out of control or pulled back)
  double insertion = 1.0;     // the insertion action applied (act/2; 1 = the constant push)
  bool retracting = false;    // the procedure pulls the wire back this step
  double omega_before = 0.0;  // omega at the start of the step (act/2's reward pays the aim by its change)
};

// What the physics steps of one env step did.
struct PhysicsSummary {
  WallForce peak;          // the largest single-node, total and tip force over the physics steps, mN
  double total_sum_mN = 0.0;  // the total force summed over the physics steps
  int steps = 0;           // physics steps taken
  int held = 0;            // of them, steps the force limit backed the wire off in
  int contacts = 0;        // the last physics step's contact count
  std::string problem;     // non-empty: the physics diverged or the wall-time limit hit (the step stopped there)
  bool time_limit = false;
};

inline double env_dt(const TaskConfig& c) { return c.frame_skip * c.dt_s; }

inline double lambda_ratio(const TaskConfig& c, const EpisodeState& s) {
  return std::clamp(s.lambda_mm / s.lambda0_mm, 0.0, c.max_lambda_ratio);
}

// Whether `tip` is within the control radius of a bifurcation of `course`.
bool near_a_bifurcation(const Course& course, const Eigen::Vector3d& tip);

// Inputs: the task, the state, the agent's action. Output: the command the action gives (the action ignored out
// of control; act/1 pushes at +1; act/2 never pulls the wire out past its start insertion).
StepCommand command_step(const NavigationTask& task, const EpisodeState& s, const Action& action);

// Inputs: the command; `limits`. Outputs: the wire advanced by frame_skip physics steps (each backed off instead
// while the last one pressed the wall harder than force_limit_N; s.withheld_mm and s.last_peak_node_mN kept), and
// the step's figures. Stops at the first diverged physics step or past the wall-time limit.
PhysicsSummary advance_physics(const NavigationTask& task, EpisodeState& s, const Control& control,
                               const StepLimits& limits);

// Inputs: the wire after a step (`first`: at reset, the history entries take the current values). Outputs:
// s.obs (theta, lambda, omega, omega_side, speed; the action entries are the caller's), the goal, the tip's progress
// along the course, whether the next action applies.
void observe_episode(const NavigationTask& task, EpisodeState& s, bool first);

// Inputs: the observed state. Outputs: the stall clocks (best progress, its step and the insertion then) moved on
// when the tip gained stuck_progress_mm.
void track_progress(const TaskConfig& c, EpisodeState& s);

// Whether the wire has stalled: act/1, no progress for stuck_steps env steps; act/2, stuck_steps full-speed pushes
// of wire put in (commanded, the withheld push included) without progress.
bool stalled(const TaskConfig& c, const EpisodeState& s);

// The step's info fields from the physics (force figures, contacts, push held, whether it pulled back).
void fill_physics_info(StepInfo& info, const PhysicsSummary& physics, bool retracting);

// Inputs: the observed state. Outputs: info.success (tip within success_radius_mm of the target) and
// info.wrong_branch; returns the bifurcation whose wrong child the tip is in (-1: none, or success).
int check_arrival(const NavigationTask& task, const EpisodeState& s, StepInfo& info);

// act/2: the observation's wrong-branch flag from this step's test, and an actor in a wrong child in control (it
// must be able to pull out). Returns whether the tip entered a wrong child this step.
bool observe_wrong_branch(EpisodeState& s, int lost, StepInfo& info);

// The force cost of the step's reward: reward_force_per_N times the newtons by which the step's peak single-node
// wall force exceeds kRuptureForceN (wall_force.hpp); 0 at or below it.
double force_cost(const TaskConfig& c, const PhysicsSummary& physics);

// The step's reward before the force cost: Eq. 3 under act/1; under act/2 the push/pull reward (reward.hpp), for
// which the command's new depth is recorded in the state.
double step_reward(const NavigationTask& task, EpisodeState& s, const StepCommand& command, bool in_wrong_branch);

// The paper's strict end (info.step_limit, stuck, wire_exhausted, out.terminated / truncated), reported once as
// info.strict_end.
void check_strict_end(const NavigationTask& task, EpisodeState& s, bool stalled, StepOutcome& out);

}  // namespace gw
