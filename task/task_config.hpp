#pragma once
// Every constant of the navigation task (paper section 2.2) in one place, with the reason for
// its value. The task model (NavigationTask) holds one; episodes never change it.
#include <string>

#include "task/action_layout.hpp"
#include "task/observation_layout.hpp"
#include "task/reward.hpp"

namespace gw {

// When the policy's action is applied (docs/architecture.md, "Trees").
enum class ControlMode {
  kAlways,             // every env step (training on single bifurcation patterns, paper 2.2.2)
  kNearBifurcation,    // only while the tip is within control_radius_mm of a bifurcation centre
  kAuto,               // kAlways when the path has at most one bifurcation, else kNearBifurcation
};

// How the task's lengths meet the vessel's size (issue 35; docs/vessel_scale.md).
enum class TaskScale {
  kFixed,   // the paper's millimetres, set for coronaries 1.5-4 mm across: a wrong child is entered once the tip
            // is wrong_branch_depth_mm along its centreline from the bifurcation centre, and the policy acts
            // within control_radius_mm of the centre. Every row of the results table
  kVessel,  // the same lengths measured from the walls: a wrong child is entered once the tip is inside its
            // lumen (nearer its centreline than its radius) wrong_branch_depth_mm past its ostium (where its
            // centreline leaves the parent's lumen), and the policy acts within control_radius_mm of the
            // parent's wall around the centre. In a 23 mm aorta the fixed rules call a tip on the wall beside
            // an ostium "in the branch" (the child's centreline runs ~11 mm inside the aorta) and hand the
            // policy control ~16 mm before a fork whose centre lies on the axis (results/arch_wire)
  kAuto,    // kVessel when the inlet radius exceeds wide_vessel_radius_mm, else kFixed
};

struct TaskConfig {
  // --- Driving the wire (constant push + rotation from the action) ---
  double dt_s = 0.01;                    // physics time step handed to make_wire_model
  int frame_skip = 4;                    // physics steps per env step: one env step = 0.04 s
  double push_mm_per_s = 10.0;           // constant insertion: 0.4 mm per env step, so a ~100-150 mm
                                         // training path takes ~250-400 env steps ("a few hundred")
  double max_rotation_rad_per_s = 6.283185307179586;  // action +-1 = one proximal turn per second:
                                         // a half turn (the worst re-orientation) costs 0.5 s = 5 mm of
                                         // advance, well inside the 20 mm control zone
  double initial_insertion_mm = 2.0;     // tip this far past the inlet at reset
  double max_start_tilt_rad = 0.1745329251994330;  // random start orientation: up to 10 deg off the
                                         // inlet direction (random azimuth), paper 2.2.2
  ActionLayout action = ActionLayout::kRotation;  // act/1: the paper's constant push, the action turns the
                                         // wire; act/2: the actor also sets the insertion speed in the control
                                         // zone (push/pull, docs/recovery.md); needs observation obs/5
  // --- Observation (layout in observation.hpp) ---
  double tip_sample_spacing_mm = 2.0;    // t_1..t_3 at 0, 2, 4 mm from the tip: spans the 6 mm curved
                                         // tip with several "grating" samples (paper: robustness to
                                         // shape-reconstruction noise)
  double lookahead_mm = 4.0;             // h: centerline tangent c_i taken h ahead of each sample
  double branch_direction_mm = 6.0;      // c and w (omega) = directions from a bifurcation centre to
                                         // the points this far along the correct / wrong child
  ObservationLayout observation;         // omega's plane, omega's sine, junctions (observation_layout.hpp); default
                                         // obs/3, the shipped actor's (the paper's is obs/1: docs/task_settings.md)
  double max_abs_speed_ratio = 5.0;      // s = v.c / push is clipped to +-this (bounded obs space)
  double max_lambda_ratio = 4.0;         // lambda_t / lambda_0 is clipped to [0, this]
  // --- Reward (reward.hpp) ---
  RewardShape reward{-0.5, 8.0};         // orientation sigmoid: centre -0.5, slope 8, the shipped actors' (the paper's
                                         // Eq. 3 is centre 0.1, slope 5: RewardShape's own default; reward.hpp says why)
  // --- Episode end ---
  double success_radius_mm = 4.0;        // tip within this distance of the target = success
  double wrong_branch_depth_mm = 4.0;    // failure once the tip is this far along a wrong child and
                                         // closer to it than to the correct continuation
  double control_radius_mm = 20.0;       // paper: the policy acts within 20 mm of a bifurcation centre
  TaskScale task_scale = TaskScale::kAuto;  // the two rules above in millimetres or from the walls
  double wide_vessel_radius_mm = 4.0;    // kAuto: an inlet wider than this is not a coronary (the 0.014" wire's
                                         // range, 1.5-4 mm; navigate suggests the aortic wire above it). Every
                                         // anatomy of the index has an inlet radius of 1.75-2 mm
  double intermediate_target_mm = 50.0;  // trees: lambda (observation and reward) is measured to an
                                         // intermediate target this far past each bifurcation centre along
                                         // the course (capped at the final target); the goal still advances
                                         // at the hand-over point above. 50 mm = the mean length of the
                                         // training patterns' target branches (29-72 mm), so lambda meets a
                                         // bifurcation in the range training showed it (never near 0 before
                                         // the hand-over, where a policy has learnt that rolling is free).
                                         // 0 = at the hand-over point (before 2026-11-28)
  ControlMode control_mode = ControlMode::kAuto;
  int max_steps = 0;                     // step limit; 0 = auto: path_length * factor / advance per step
  double max_steps_path_factor = 2.5;    //   (+ 50), i.e. 2.5x the steps a wire that never buckles needs
  int stuck_steps = 60;                  // truncate when the tip's progress along the path has not grown
  double stuck_progress_mm = 1.0;        //   by stuck_progress_mm in stuck_steps env steps (24 mm pushed)
  double wire_reserve_mm = 5.0;          // truncate when less than this much wire is left outside
  // --- Recovery (issue 37 item 1a; docs/recovery.md). 0 attempts = the paper's strict task: every
  // episode bit for bit as before. With K > 0 the episode does not end where the strict one does (first
  // wrong branch, a stall): it reports that step as the strict end (StepInfo::strict_end) and goes on:
  // pull the wire back (negative push, no action applied) until the tip's projection on the course is
  // recovery_retract_mm before the centre of the bifurcation it was lost at (a stall away from one:
  // before where it stalled), turning the proximal end by k * recovery_turn_rad on the k-th, then advance
  // again under the controller. At most K pull-backs; the procedure may run recovery_time_s of
  // simulated time past the strict step limit.
  int recovery_attempts = 0;
  double recovery_retract_mm = 20.0;     // = control_radius_mm: the tip re-enters the control zone at its
                                         // edge, with the whole zone to re-aim in
  double recovery_pull_mm_per_s = 10.0;  // retraction speed (the push speed: 0.4 mm per env step)
  double recovery_turn_rad = 1.5707963267948966;  // pull-back k turns the proximal end by k times this while
                                         // pulling: with a quarter turn the tip's bend leaves the fork a
                                         // quarter turn apart on each of the 4 approaches (0, 90, 270, 180
                                         // deg for K = 3). A controller that re-aims only starts its sweep
                                         // elsewhere; one that never turns (push-only) would otherwise retry
                                         // the same approach (half turns: the 3rd retry repeats the 1st)
  double recovery_time_s = 30.0;         // simulated seconds allowed past the strict step limit (3 attempts
                                         // of ~2.5 s back and ~2.5 s forward each fit with room)
  // Under act/2 the actor recovers by itself: nothing is pulled for it. With K > 0 the strict end is reported
  // as above and the procedure goes on under the actor, which may pull back out of the wrong child; its
  // (K+1)-th entry into a wrong child ends the procedure as a failure, and the same recovery_time_s bounds it.
  // A stall under act/2 is wire pushed in without progress (stuck_steps full-speed pushes, 24 mm: the strict
  // rule under the constant push), so stopping to aim is not one; it ends the strict episode and the procedure.
  // StepInfo::recovery_attempts counts the entries into a wrong child that the procedure went on after.
  // With recovery_assist (act/2 only; act/1 is always recovered by the wrapper) the wrapper's pull-back, turn and
  // re-aim above also step in for the actor where it does not recover by itself: on a stall (which then uses one
  // of the K attempts instead of ending the procedure; with none left it ends it) and when the tip has stayed in
  // a wrong child for stuck_steps env steps (its entry already used an attempt, so this pull-back uses none), and,
  // once the strict episode is over, on a standstill: neither the tip's progress nor the commanded insertion has
  // moved stuck_progress_mm for stuck_steps env steps outside a wrong child (one attempt; with none left nothing is
  // done). The actor is handed the wire back at the end of the pull-back. Off: every act/2 run before it, bit for
  // bit.
  bool recovery_assist = false;
  // The act/2 reward (reward.hpp, push_pull_reward): the progress term earned by new depth and the aim by its
  // change, less this per env step while the tip is in a wrong child.
  double reward_wrong_branch = 1.0;
  // ... and less this every env step (a cost of time; 0.25 = the shipped push/pull actor's, 0 = the first push/pull
  // run's reward). Without it stopping is free (reward.hpp says why that matters).
  double reward_time_per_step = 0.25;
  // --- Force penalty (issue 37 item 4; 0 = the paper's reward, Eq. 3) ---
  // Each env step's reward loses this per newton by which the step's peak single-node wall force (StepInfo::
  // wall_force_peak_node_mN / 1000) exceeds 1.5 N (kRuptureForceN, the vessel-rupture threshold the safety
  // figures use): pressing within the safe force is free, a node at 3 N for a step costs 1.5 x this, a jam at
  // 50 N 48.5 x this. Off for the paper's column and the shipped actors. (Before 2026-12-06: this times the
  // step's peak total wall force, no threshold; results/generalist/README.md says why it changed.)
  double reward_force_per_N = 0.0;
  // --- Force limit (issue 37; docs/recovery.md "Force limit"; 0 = off: the paper's task, every table row) ---
  // What a clinician does on feeling resistance: stop, let go of the torque, ease back. While the wire presses the
  // wall harder than this (the largest single-node wall force of the last physics step, N), the next physics step
  // pulls the wire back at push_mm_per_s and does not turn it, whatever was asked (a pull-back already as fast goes
  // on; at the start insertion the wire is held). The commanded forward push counts as pushed for the stall tests:
  // under the constant push the tip stops progressing (a stall, which recovery answers with a pull-back); under
  // act/2 it counts as wire pushed in without progress. An idealised sensor: the simulator knows the wall force per
  // node, a robot measures the force at the proximal end.
  double force_limit_N = 0.0;
  // --- Junctions beyond the two-way fork (issue 41; observation.junctions) ---
  double close_junction_diameters = 2.0;  // kCombined: forks closer than this many diameters of the vessel
                                          // between them (the correct child's radius over its first 8 mm)
                                          // are aimed at together; the "one to two diameters"
};

// Throws std::invalid_argument naming the first field out of range.
void check_task_config(const TaskConfig& config);

// "always" | "near_bifurcation" | "auto"; throws std::invalid_argument for anything else.
ControlMode parse_control_mode(const std::string& text);
const char* control_mode_name(ControlMode mode);

// "fixed" | "vessel" | "auto"; throws std::invalid_argument for anything else.
TaskScale parse_task_scale(const std::string& text);
const char* task_scale_name(TaskScale scale);

}  // namespace gw
