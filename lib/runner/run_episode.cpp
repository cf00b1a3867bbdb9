#include "lib/runner/run_episode.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "task/observation.hpp"
#include "engine/wire/wire_queries.hpp"

namespace gw {
namespace {

// The observation entries a trace keeps: obs/3's twelve (every layout but obs/5 and obs/8), or all of the layout's.
int traced_entries(const TaskConfig& c) { return std::max(kSideObservationSize, c.observation.size()); }

void record_frame(const NavigationTask& task, const EpisodeState& s, const StepInfo& info, const Action& action,
                  bool in_control, int frame, const TraceOptions& options, EpisodeTrace& trace) {
  trace.time_s.push_back(s.wire.time);
  trace.tip.push_back(s.tip);
  trace.action.push_back(action.rotation);
  if (task.config.action == ActionLayout::kRotationInsertion) trace.insertion.push_back(action.insertion);
  trace.agent_in_control.push_back(in_control);
  trace.observation.emplace_back(s.obs.begin(), s.obs.begin() + traced_entries(task.config));
  trace.goal.push_back(s.goal);
  trace.wall_force_peak_node_mN.push_back(info.wall_force_peak_node_mN);
  trace.wall_force_peak_total_mN.push_back(info.wall_force_peak_total_mN);
  trace.wall_force_mean_total_mN.push_back(info.wall_force_mean_total_mN);
  trace.tip_force_mN.push_back(info.tip_force_mN);
  if (task.config.recovery_attempts > 0) trace.retracting.push_back(info.retracting);
  if (task.config.force_limit_N > 0) trace.push_held_s.push_back(info.push_held_steps * task.config.dt_s);
  if (options.wire_shape_every > 0 && frame % options.wire_shape_every == 0) {
    trace.wire_shapes.push_back(inserted_node_positions(wire_of(task, s.anatomy), s.wire));
    trace.wire_shape_frame.push_back(frame);
  }
}

// Maps the task's end flags onto the trace outcomes the report and the summary count.
void set_outcome(const StepInfo& i, std::string& outcome, std::string& detail) {
  const std::string where = "goal " + std::to_string(i.goal + 1) + " of " + std::to_string(i.goals);
  if (i.success) {
    outcome = "success";
  } else if (i.wrong_branch) {
    outcome = "wrong_branch";
    detail = "entered a wrong branch before " + where;
  } else if (!i.problem.empty() && !i.time_limit) {
    outcome = "diverged";
    detail = i.problem;
  } else if (i.stuck) {
    outcome = "stuck";
    detail = "no progress at " + std::to_string(static_cast<int>(i.progress_mm)) + " mm along the path (" + where + ")";
  } else {
    outcome = "timeout";
    detail = i.time_limit ? i.problem : i.wire_exhausted ? "wire fully inserted" : "step limit reached";
  }
}

// One pass from the inlet: reset -> (observe -> act -> step) until the task ends it; the wire's inserted
// length at the end goes to `inserted_mm` (what a tip reshape has to withdraw).
EpisodeTrace run_pass(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed,
                      Controller& controller, const TraceOptions& options, double& inserted_mm) {
  EpisodeState s = reset_episode(task, anatomy, target_id, seed);
  controller.begin_episode();
  EpisodeTrace trace;
  trace.anatomy = task.anatomies[static_cast<std::size_t>(s.anatomy)].name;
  trace.controller = controller.name();
  trace.target_id = s.target_id;
  trace.seed = seed;
  for (int i = 0; i < traced_entries(task.config); ++i) trace.observation_names.emplace_back(observation_names()[i]);
  const int attempts = task.config.recovery_attempts;
  trace.recovery_attempts_allowed = attempts;
  int frame = 0;
  record_frame(task, s, StepInfo{}, Action{0.0, 0.0}, s.in_control, frame, options, trace);
  // omega when the tip reached each bifurcation centre on the course (goal k belongs to bifurcation k).
  // (Their arcs are read from current_course: on a moving wall the course changes shape every step.)
  std::vector<double> omega_at_centre(s.course->bifurcations.size(), std::numeric_limits<double>::quiet_NaN());
  std::size_t next_centre = 0;
  bool strict_over = false;
  for (;;) {
    const bool in_control = s.in_control;
    const Action action = in_control ? controller.act(s.obs) : Action{};
    const StepOutcome out = step_episode(task, s, action, StepLimits{options.step_time_limit_s});
    ++frame;
    record_frame(task, s, out.info, action, in_control, frame, options, trace);
    for (; !strict_over && next_centre < omega_at_centre.size() &&
           s.progress_mm >= current_course(s).bifurcations[next_centre].arc;
         ++next_centre)
      omega_at_centre[next_centre] = s.obs[obs_index::kOmega];
    if (out.info.strict_end) {  // the paper's episode ends here (with recovery the procedure may go on)
      strict_over = true;
      set_outcome(out.info, trace.outcome, trace.detail);
      if (attempts > 0) trace.strict_end_frame = frame;
      if (out.info.wrong_branch) {
        const auto lost = static_cast<std::size_t>(out.info.goal);
        const bool reached = lost < omega_at_centre.size() && !std::isnan(omega_at_centre[lost]);
        trace.omega_at_loss = reached ? omega_at_centre[lost] : s.obs[obs_index::kOmega];
      }
    }
    if (out.terminated || out.truncated) {
      if (attempts > 0) {
        set_outcome(out.info, trace.recovery_outcome, trace.recovery_detail);
        trace.recovery_attempts_used = out.info.recovery_attempts;
      }
      break;
    }
  }
  if ((trace.wire_shape_frame.empty() || trace.wire_shape_frame.back() != frame)) {
    trace.wire_shapes.push_back(inserted_node_positions(wire_of(task, s.anatomy), s.wire));
    trace.wire_shape_frame.push_back(frame);
  }
  inserted_mm = s.wire.inserted_length_mm;
  return trace;
}

}  // namespace

EpisodeTrace run_episode(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed,
                         Controller& controller, const TraceOptions& options) {
  double inserted_mm = 0.0;
  EpisodeTrace trace = run_pass(task, anatomy, target_id, seed, controller, options, inserted_mm);
  if (!options.reshaped) return trace;
  // Tip reshape: a procedure that ended short of the target (a physics failure is not a procedure's end)
  // is withdrawn at the recovery pull speed and navigated again with the reshaped tip.
  trace.reshape_tip_per_mm = wire_of(*options.reshaped, anatomy).params.tip_curvature_per_mm;
  trace.reshape_tip_length_mm = wire_of(*options.reshaped, anatomy).params.tip_length_mm;
  const std::string& end = procedure_outcome(trace);
  if (end == "success" || end == "diverged") return trace;
  trace.reshape_withdrawal_s =
      std::max(0.0, inserted_mm - task.config.initial_insertion_mm) / task.config.recovery_pull_mm_per_s;
  double unused = 0.0;
  trace.reshaped.push_back(run_pass(*options.reshaped, anatomy, target_id, seed, controller, options, unused));
  return trace;
}

NavigationTask make_reshaped_task(const NavigationTask& task, double tip_curvature_per_mm, double tip_length_mm) {
  if (!(tip_curvature_per_mm > 0) || !std::isfinite(tip_curvature_per_mm))
    throw std::invalid_argument("tip reshape: the curvature must be a number above 0 (1/mm), got " +
                                std::to_string(tip_curvature_per_mm));
  std::vector<Anatomy> anatomies = task.anatomies;  // each keeps its scene; its wire becomes the reshaped one
  for (std::size_t a = 0; a < anatomies.size(); ++a) {
    WireParams wire = task.wires[a].params;
    if (tip_length_mm != 0.0) {
      if (!(tip_length_mm > 0) || !std::isfinite(tip_length_mm) || tip_length_mm >= wire.length_mm)
        throw std::invalid_argument("tip reshape: the tip length must be 0 (the wire's own) or a number above 0 "
                                    "(mm) shorter than the wire (" + std::to_string(wire.length_mm) + " mm), got " +
                                    std::to_string(tip_length_mm));
      wire.tip_length_mm = tip_length_mm;
    }
    wire.tip_curvature_per_mm = tip_curvature_per_mm;
    anatomies[a].wire = std::make_shared<const WireParams>(wire);
  }
  return make_navigation_task(task.config, task.wires.front().params, std::move(anatomies));
}

}  // namespace gw
