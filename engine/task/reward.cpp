#include "engine/task/reward.hpp"

#include <cmath>

namespace gw {

double navigation_reward(double omega, double lambda_ratio, double action, const RewardShape& shape) {
  const double orientation = 2.0 / (1.0 + std::exp(shape.omega_slope * (omega - shape.omega_centre))) - 1.0;
  const double progress = 0.5 * (1.0 - lambda_ratio);
  const double effort = -0.2 * std::abs(action);
  return orientation + progress + effort;
}

}  // namespace gw
