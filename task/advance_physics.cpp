// Stage advance_physics (episode_stages.hpp): frame_skip physics steps under the force limit.
#include <algorithm>
#include <chrono>

#include "task/episode_stages.hpp"

namespace gw {

namespace {

// TaskConfig::force_limit_N: what a clinician does on feeling resistance. While the last physics step pressed the
// wall harder than the limit at one node, the wire is pulled back at the push speed and not turned (held at the start
// insertion); a pull-back already as fast goes on. The forward push given up is counted in s.force.withheld_mm.
Control limit_force(const TaskConfig& c, EpisodeState& s, const Control& control, int& held) {
  Control applied = control;
  const double limit_mN = 1e3 * c.force_limit_N;  // 0: off
  if (limit_mN > 0 && s.force.last_peak_node_mN > limit_mN) {
    const double back = s.wire.inserted_length_mm <= c.initial_insertion_mm ? 0.0 : -c.push_mm_per_s;
    if (control.push_mm_per_s > back) {
      applied.push_mm_per_s = back;
      applied.rotate_rad_per_s = 0.0;
      s.force.withheld_mm += (std::max(control.push_mm_per_s, 0.0) - back) * c.dt_s;
      ++held;
    }
  }
  return applied;
}

}  // namespace

PhysicsSummary advance_physics(const NavigationTask& task, EpisodeState& s, const Control& control,
                               const StepLimits& limits) {
  const TaskConfig& c = task.config;
  const Anatomy& anatomy = task.anatomies[static_cast<size_t>(s.anatomy)];
  PhysicsSummary out;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < c.frame_skip; ++k) {
    const Control applied = limit_force(c, s, control, out.held);
    const StepReport report = step(wire_of(task, s.anatomy), anatomy.scene.get(), applied, s.wire);
    out.contacts = report.contacts;
    if (!report.ok) {
      out.problem = "physics diverged: " + report.problem;
      break;
    }
    const WallForce f = wall_force(wire_of(task, s.anatomy), s.wire);
    s.force.last_peak_node_mN = f.peak_node_mN;
    out.peak.peak_node_mN = std::max(out.peak.peak_node_mN, f.peak_node_mN);
    out.peak.total_mN = std::max(out.peak.total_mN, f.total_mN);
    out.peak.tip_mN = std::max(out.peak.tip_mN, f.tip_mN);
    out.total_sum_mN += f.total_mN;
    ++out.steps;
    if (limits.wall_time_s > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > limits.wall_time_s) {
      out.time_limit = true;
      out.problem = "env step exceeded its time limit of " + std::to_string(limits.wall_time_s) + " s";
      break;
    }
  }
  return out;
}

}  // namespace gw
