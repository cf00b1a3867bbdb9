#include "task/observation.hpp"

#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <stdexcept>

namespace gw {

const std::array<const char*, kObservationSize>& observation_names() {
  static const std::array<const char*, kObservationSize> names = {
      "theta_t_1", "theta_t_2", "theta_t_3", "theta_prev_1", "theta_prev_2", "theta_prev_3",
      "lambda_t",  "lambda_prev", "action",  "omega",        "speed",        "omega_side",
      "insertion", "wrong_branch", "tip_force"};
  return names;
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
  low[obs_index::kInsertion] = -1.0;
  high[obs_index::kInsertion] = 1.0;
  low[obs_index::kWrongBranch] = 0.0;
  high[obs_index::kWrongBranch] = 1.0;
  low[obs_index::kTipForce] = 0.0;
  high[obs_index::kTipForce] = kTipForceCap;
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
