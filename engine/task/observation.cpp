#include "engine/task/observation.hpp"

#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <stdexcept>

namespace gw {

const std::array<const char*, kObservationSize>& observation_names() {
  static const std::array<const char*, kObservationSize> names = {
      "theta_t_1", "theta_t_2", "theta_t_3", "theta_prev_1", "theta_prev_2", "theta_prev_3",
      "lambda_t",  "lambda_prev", "action",  "omega",        "speed",        "omega_side"};
  return names;
}

namespace {
// omega_side is measured about the approach direction only: the paper's plane (normal to the correct
// branch) is the one where omega is blind, and nothing was trained on that combination.
// obs/4 is obs/3 with junctions combined (TaskConfig::junctions): the same entries, which mean the same on
// a two-way fork with no fork close behind it.
struct Layout {
  const char* name;
  OmegaPlane plane;
  bool omega_side;
  JunctionModel junctions;
};
constexpr Layout kLayouts[] = {{"guidewire-nav/obs/1", OmegaPlane::kCorrectBranch, false, JunctionModel::kSeparate},
                               {"guidewire-nav/obs/2", OmegaPlane::kApproach, false, JunctionModel::kSeparate},
                               {"guidewire-nav/obs/3", OmegaPlane::kApproach, true, JunctionModel::kSeparate},
                               {"guidewire-nav/obs/4", OmegaPlane::kApproach, true, JunctionModel::kCombined}};
}  // namespace

const char* observation_layout(const TaskConfig& config) {
  for (const Layout& l : kLayouts)
    if (l.plane == config.omega_plane && l.omega_side == config.omega_side && l.junctions == config.junctions)
      return l.name;
  if (config.omega_side && config.omega_plane != OmegaPlane::kApproach)
    throw std::invalid_argument("omega_side needs omega's plane 'approach' (no layout has it in the paper's plane)");
  throw std::invalid_argument("combined junctions need omega's plane 'approach' and omega_side (layout obs/4)");
}

int observation_size(const TaskConfig& config) {
  return config.omega_side ? kObservationSize : kPaperObservationSize;
}

void apply_observation_layout(const std::string& layout, TaskConfig& config) {
  std::string known;
  for (const Layout& l : kLayouts) {
    if (layout == l.name) {
      config.omega_plane = l.plane;
      config.omega_side = l.omega_side;
      config.junctions = l.junctions;
      return;
    }
    known += std::string(known.empty() ? "" : ", ") + l.name;
  }
  throw std::invalid_argument("observation layout '" + layout + "' is not one of " + known);
}

void observation_bounds(const TaskConfig& config, Observation& low, Observation& high) {
  for (int i = 0; i < 2 * kThetaCount; ++i) {
    low[i] = -1.0;
    high[i] = 1.0;
  }
  low[obs_index::kLambda] = low[obs_index::kLambdaPrev] = 0.0;
  high[obs_index::kLambda] = high[obs_index::kLambdaPrev] = config.max_lambda_ratio;
  low[obs_index::kAction] = low[obs_index::kOmega] = low[obs_index::kOmegaSide] = -1.0;
  high[obs_index::kAction] = high[obs_index::kOmega] = high[obs_index::kOmegaSide] = 1.0;
  low[obs_index::kSpeed] = -config.max_abs_speed_ratio;
  high[obs_index::kSpeed] = config.max_abs_speed_ratio;
}

namespace {
// The curvature projected on omega's plane, k_p, and omega's scale max(|k_p|, kappa_rest/2): a unit
// in-plane direction dotted with k_p / scale gives a cosine while the tip is curved, fading as the wall
// straightens it.
struct InPlaneCurvature {
  Eigen::Vector3d kp;
  double scale;
};
InPlaneCurvature in_plane(const Eigen::Vector3d& curvature, const Eigen::Vector3d& plane_normal, double rest_curvature) {
  const Eigen::Vector3d kp = curvature - curvature.dot(plane_normal) * plane_normal;
  return {kp, std::max(kp.norm(), 0.5 * rest_curvature)};
}
double scaled_dot(const InPlaneCurvature& k, const Eigen::Vector3d& direction) {
  if (!(k.scale > 0.0)) return 0.0;
  return std::clamp(k.kp.dot(direction) / k.scale, -1.0, 1.0);
}
}  // namespace

double wrong_branch_alignment(const Eigen::Vector3d& curvature, const Eigen::Vector3d& plane_normal,
                              const Eigen::Vector3d& wrong_in_plane, double rest_curvature) {
  return scaled_dot(in_plane(curvature, plane_normal, rest_curvature), wrong_in_plane);
}

double wrong_branch_side(const Eigen::Vector3d& curvature, const Eigen::Vector3d& plane_normal,
                         const Eigen::Vector3d& wrong_in_plane, double rest_curvature) {
  return scaled_dot(in_plane(curvature, plane_normal, rest_curvature), plane_normal.cross(wrong_in_plane));
}

Eigen::Vector3d curvature_from_tangents(const Eigen::Vector3d& tip_tangent, const Eigen::Vector3d& back_tangent,
                                        double arc_between) {
  return (tip_tangent - back_tangent) / arc_between;
}

}  // namespace gw
