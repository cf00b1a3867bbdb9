#include "engine/task/observation.hpp"

#include <algorithm>
#include <stdexcept>

namespace gw {

const std::array<const char*, kObservationSize>& observation_names() {
  static const std::array<const char*, kObservationSize> names = {
      "theta_t_1", "theta_t_2", "theta_t_3", "theta_prev_1", "theta_prev_2", "theta_prev_3",
      "lambda_t",  "lambda_prev", "action",  "omega",        "speed"};
  return names;
}

const char* observation_layout(OmegaPlane plane) {
  return plane == OmegaPlane::kCorrectBranch ? "guidewire-nav/obs/1" : "guidewire-nav/obs/2";
}

OmegaPlane omega_plane_of_layout(const std::string& layout) {
  for (OmegaPlane p : {OmegaPlane::kCorrectBranch, OmegaPlane::kApproach})
    if (layout == observation_layout(p)) return p;
  throw std::invalid_argument("observation layout '" + layout + "' is not one of " +
                              observation_layout(OmegaPlane::kCorrectBranch) + ", " +
                              observation_layout(OmegaPlane::kApproach));
}

void observation_bounds(const TaskConfig& config, Observation& low, Observation& high) {
  for (int i = 0; i < 2 * kThetaCount; ++i) {
    low[i] = -1.0;
    high[i] = 1.0;
  }
  low[obs_index::kLambda] = low[obs_index::kLambdaPrev] = 0.0;
  high[obs_index::kLambda] = high[obs_index::kLambdaPrev] = config.max_lambda_ratio;
  low[obs_index::kAction] = low[obs_index::kOmega] = -1.0;
  high[obs_index::kAction] = high[obs_index::kOmega] = 1.0;
  low[obs_index::kSpeed] = -config.max_abs_speed_ratio;
  high[obs_index::kSpeed] = config.max_abs_speed_ratio;
}

double wrong_branch_alignment(const Eigen::Vector3d& curvature, const Eigen::Vector3d& plane_normal,
                              const Eigen::Vector3d& wrong_in_plane, double rest_curvature) {
  const Eigen::Vector3d kp = curvature - curvature.dot(plane_normal) * plane_normal;
  const double scale = std::max(kp.norm(), 0.5 * rest_curvature);
  if (!(scale > 0.0)) return 0.0;
  return std::clamp(kp.dot(wrong_in_plane) / scale, -1.0, 1.0);
}

Eigen::Vector3d curvature_from_tangents(const Eigen::Vector3d& tip_tangent, const Eigen::Vector3d& back_tangent,
                                        double arc_between) {
  return (tip_tangent - back_tangent) / arc_between;
}

}  // namespace gw
