#include "task/course.hpp"
#include "base/util/median.hpp"

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

// The unit wrong direction w_p of child `wrong` seen from bifurcation `cb` (its centre, correct direction c
// and omega's plane normal): w itself (paper) or w - c (approach plane), projected on the plane; zero
// when parallel to the normal.
Eigen::Vector3d wrong_in_plane(const CourseBifurcation& cb, const Polyline& wrong, const TaskConfig& config) {
  const Eigen::Vector3d wd = child_direction(wrong, cb.centre, config.branch_direction_mm);
  const bool paper = config.observation.omega_plane == OmegaPlane::kCorrectBranch;
  const Eigen::Vector3d& n = cb.omega_normal;
  const Eigen::Vector3d away = paper ? wd : Eigen::Vector3d(wd - cb.correct_direction);
  Eigen::Vector3d wp = away - away.dot(n) * n;
  const double len = wp.norm();
  return len > 1e-6 ? Eigen::Vector3d(wp / len) : Eigen::Vector3d::Zero();
}

// Median radius of a branch over its first 8 mm (the junction's own bulge is one or two points of it).
double radius_after_origin(const CenterlineBranch& branch) {
  std::vector<double> r;
  double arc = 0.0;
  for (size_t i = 0; i < branch.radii.size() && arc <= 8.0; ++i) {
    r.push_back(branch.radii[i]);
    if (i + 1 < branch.points.size()) arc += (branch.points[i + 1] - branch.points[i]).norm();
  }
  return r.empty() ? 0.0 : median(r);
}

// Resolves config.task_scale for `graph` into course.vessel_scale (kAuto: a wide inlet).
void resolve_task_scale(const CenterlineGraph& graph, const TaskConfig& config, Course& course) {
  switch (config.task_scale) {
    case TaskScale::kFixed: course.vessel_scale = false; break;
    case TaskScale::kVessel: course.vessel_scale = true; break;
    case TaskScale::kAuto: course.vessel_scale = graph.inlet.radius > config.wide_vessel_radius_mm; break;
  }
}

// Appends path bifurcation `pb` (the k-th on the path) to course.bifurcations: its centre located on
// course.line, directions, wrong branches and control radius (vessel scale: lumens over `course_radius`).
void add_bifurcation(const CenterlineGraph& graph, const std::vector<Polyline>& branch_lines,
                     const TaskConfig& config, const RadiusProfile& course_radius, const PathBifurcation& pb,
                     size_t k, Course& course) {
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
  cb.omega_normal = config.observation.omega_plane == OmegaPlane::kCorrectBranch ? c : cb.approach_direction;
  // Paper: w itself. Approach plane: from the correct towards the wrong branch, as the rolled tip sees it.
  for (int w : pb.wrong_children) {
    cb.wrong_branches.push_back(w);
    cb.wrong_in_plane.push_back(wrong_in_plane(cb, branch_lines.at(static_cast<size_t>(w)), config));
  }
  cb.control_radius = config.control_radius_mm;
  if (course.vessel_scale) {
    for (int w : pb.wrong_children) {
      const CenterlineBranch& child = graph.branches.at(static_cast<size_t>(w));
      cb.wrong_lumens.push_back(make_branch_lumen(child.points, child.radii, course.line, course_radius));
    }
    cb.parent_radius = median_radius(course_radius, cb.arc - 8.0, cb.arc);
    cb.control_radius += cb.parent_radius;
  }
  course.bifurcations.push_back(std::move(cb));
}

// JunctionModel::kCombined: appends to each of course.bifurcations the wrong directions of the path's
// bifurcations that follow within close_junction_diameters diameters of the vessel between them.
void add_close_wrong_directions(const CenterlineGraph& graph, const std::vector<Polyline>& branch_lines,
                                const TargetPath& path, const TaskConfig& config, Course& course) {
  for (size_t k = 0; k < course.bifurcations.size(); ++k) {
    const double diameter =
        2.0 * radius_after_origin(graph.branches.at(static_cast<size_t>(path.bifurcations[k].correct_child)));
    CourseBifurcation& cb = course.bifurcations[k];
    for (size_t j = k + 1; j < course.bifurcations.size(); ++j) {
      if (course.bifurcations[j].arc - cb.arc >= config.close_junction_diameters * diameter) break;
      for (int w : path.bifurcations[j].wrong_children)
        cb.wrong_in_plane.push_back(wrong_in_plane(cb, branch_lines.at(static_cast<size_t>(w)), config));
    }
  }
}

// course.goal_arc and course.lambda_arc: one goal per bifurcation past its control zone, then the target.
void set_goals(const TaskConfig& config, Course& course) {
  const size_t nb = course.bifurcations.size();
  for (size_t k = 0; k + 1 < nb; ++k) {
    // Past the control zone, but before the next bifurcation's centre.
    const double next = course.bifurcations[k + 1].arc;
    const double here = course.bifurcations[k].arc;
    course.goal_arc.push_back(std::min(here + course.bifurcations[k].control_radius, 0.5 * (here + next)));
    // Never before the hand-over point (so 0 = lambda to the hand-over point), never past the target.
    course.lambda_arc.push_back(
        std::max(course.goal_arc.back(), std::min(here + config.intermediate_target_mm, course.line.length)));
  }
  course.goal_arc.push_back(course.line.length);
  course.lambda_arc.push_back(course.line.length);
}

// Resolves config.control_mode into course.policy_always (kAuto: at most one bifurcation on the course).
void resolve_control_mode(const TaskConfig& config, Course& course) {
  const size_t nb = course.bifurcations.size();
  switch (config.control_mode) {
    case ControlMode::kAlways: course.policy_always = true; break;
    case ControlMode::kNearBifurcation: course.policy_always = false; break;
    case ControlMode::kAuto: course.policy_always = nb <= 1; break;
  }
}

}  // namespace

Course make_course(const CenterlineGraph& graph, const std::vector<Polyline>& branch_lines, int target_id,
                   const TaskConfig& config) {
  const TargetPath path = plan_path(graph, target_id);
  Course course;
  course.target_id = target_id;
  course.target = graph.targets.at(static_cast<size_t>(target_id - 1)).position;
  course.line = make_polyline(path.points);
  resolve_task_scale(graph, config, course);
  const RadiusProfile course_radius =
      course.vessel_scale ? make_radius_profile(path.points, path.radii) : RadiusProfile{};
  for (size_t k = 0; k < path.bifurcations.size(); ++k)
    add_bifurcation(graph, branch_lines, config, course_radius, path.bifurcations[k], k, course);
  // Closely spaced forks (JunctionModel::kCombined): a bifurcation also aims away from the wrong children
  // of those that follow within close_junction_diameters diameters of the vessel between them.
  if (config.observation.junctions == JunctionModel::kCombined)
    add_close_wrong_directions(graph, branch_lines, path, config, course);
  set_goals(config, course);
  resolve_control_mode(config, course);
  return course;
}

}  // namespace gw
