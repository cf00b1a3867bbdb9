#include "engine/task/course.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace gw {

namespace {

// Direction from a bifurcation centre to the point `distance` along a child branch.
Eigen::Vector3d child_direction(const Polyline& child, const Eigen::Vector3d& centre, double distance) {
  const Eigen::Vector3d d = polyline_point(child, std::min(distance, child.length)) - centre;
  const double n = d.norm();
  return n > 1e-9 ? Eigen::Vector3d(d / n) : child.tangents.front();
}

}  // namespace

Course make_course(const CenterlineGraph& graph, const std::vector<Polyline>& branch_lines, int target_id,
                   const TaskConfig& config) {
  const TargetPath path = plan_path(graph, target_id);
  Course course;
  course.target_id = target_id;
  course.target = graph.targets.at(static_cast<size_t>(target_id - 1)).position;
  course.line = make_polyline(path.points);

  for (size_t k = 0; k < path.bifurcations.size(); ++k) {
    const PathBifurcation& pb = path.bifurcations[k];
    const auto bit = std::find_if(graph.bifurcations.begin(), graph.bifurcations.end(),
                                  [&](const Bifurcation& b) { return b.id == pb.bifurcation; });
    if (bit == graph.bifurcations.end())
      throw std::invalid_argument("path uses unknown bifurcation " + std::to_string(pb.bifurcation));
    CourseBifurcation cb;
    cb.bifurcation_id = pb.bifurcation;
    cb.centre = bit->position;
    // The centre is the first point of the correct child; locate it on the course polyline.
    const PolylineProjection at = project_onto_polyline(course.line, cb.centre,
                                                        k == 0 ? 0 : course.bifurcations.back().first_segment);
    cb.arc = at.arc;
    cb.first_segment = polyline_segment_at(course.line, at.arc + 1e-6);
    const Polyline& correct = branch_lines.at(static_cast<size_t>(pb.correct_child));
    cb.correct_direction = child_direction(correct, cb.centre, config.branch_direction_mm);
    const Eigen::Vector3d& c = cb.correct_direction;
    const Eigen::Vector3d before = polyline_point(course.line, std::max(0.0, cb.arc - config.branch_direction_mm));
    const Eigen::Vector3d approach = cb.centre - before;
    cb.approach_direction = approach.norm() > 1e-9 ? Eigen::Vector3d(approach.normalized()) : c;
    const bool paper = config.omega_plane == OmegaPlane::kCorrectBranch;
    cb.omega_normal = paper ? c : cb.approach_direction;
    const Eigen::Vector3d& n = cb.omega_normal;
    for (int w : pb.wrong_children) {
      const Eigen::Vector3d wd = child_direction(branch_lines.at(static_cast<size_t>(w)), cb.centre,
                                                 config.branch_direction_mm);
      // Paper: w itself. Approach plane: from the correct towards the wrong branch, as the rolled tip sees it.
      const Eigen::Vector3d away = paper ? wd : Eigen::Vector3d(wd - c);
      Eigen::Vector3d wp = away - away.dot(n) * n;
      const double len = wp.norm();
      wp = len > 1e-6 ? Eigen::Vector3d(wp / len) : Eigen::Vector3d::Zero();
      cb.wrong_branches.push_back(w);
      cb.wrong_in_plane.push_back(wp);
    }
    course.bifurcations.push_back(std::move(cb));
  }

  const size_t nb = course.bifurcations.size();
  for (size_t k = 0; k + 1 < nb; ++k) {
    // Past the control zone, but before the next bifurcation's centre.
    const double next = course.bifurcations[k + 1].arc;
    const double here = course.bifurcations[k].arc;
    course.goal_arc.push_back(std::min(here + config.control_radius_mm, 0.5 * (here + next)));
    // Never before the hand-over point (so 0 = lambda to the hand-over point), never past the target.
    course.lambda_arc.push_back(
        std::max(course.goal_arc.back(), std::min(here + config.intermediate_target_mm, course.line.length)));
  }
  course.goal_arc.push_back(course.line.length);
  course.lambda_arc.push_back(course.line.length);
  switch (config.control_mode) {
    case ControlMode::kAlways: course.policy_always = true; break;
    case ControlMode::kNearBifurcation: course.policy_always = false; break;
    case ControlMode::kAuto: course.policy_always = nb <= 1; break;
  }
  return course;
}

}  // namespace gw
