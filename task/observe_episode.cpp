#include <algorithm>

#include "task/bifurcation_omega.hpp"
#include "task/episode_stages.hpp"

namespace gw {

bool near_a_bifurcation(const Course& course, const Eigen::Vector3d& tip) {
  for (const CourseBifurcation& b : course.bifurcations)
    if ((tip - b.centre).norm() <= b.control_radius) return true;
  return false;
}

void observe_episode(const NavigationTask& task, EpisodeState& s, bool first) {
  const TaskConfig& c = task.config;
  const GraphMotion& motion = task.graph_motions[static_cast<size_t>(s.anatomy)];
  if (motion.points > 0)  // a moving wall: the course where the vessel is now (course_shape.hpp)
    course_shape_at(task.anatomies[static_cast<size_t>(s.anatomy)], motion, c, s.target_id, s.wire.time, s.shape);
  const Course& course = current_course(s);
  sample_tip(wire_of(task, s.anatomy), s.wire, c.tip_sample_spacing_mm, s.samples);
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
    const double rest = wire_of(task, s.anatomy).params.tip_curvature_per_mm;
    const OmegaReading reading = bifurcation_omega(b, kappa, rest, c.observation.junctions);
    omega = reading.omega;
    side = reading.side;
  }
  o[obs_index::kOmega] = omega;
  o[obs_index::kOmegaSide] = side;

  s.in_control = course.policy_always || near_a_bifurcation(course, tip);
}


}  // namespace gw
