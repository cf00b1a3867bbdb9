#include "engine/task/reward.hpp"

#include <cmath>

namespace gw {

double navigation_reward(double omega, double lambda_ratio, double action) {
  const double orientation = 2.0 / (1.0 + std::exp(5.0 * (omega - 0.1))) - 1.0;
  const double progress = 0.5 * (1.0 - lambda_ratio);
  const double effort = -0.2 * std::abs(action);
  return orientation + progress + effort;
}

}  // namespace gw
