#include "task/reward.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gw {

namespace {
// Eq. 3's three terms.
double orientation_term(double omega, const RewardShape& shape) {
  return 2.0 / (1.0 + std::exp(shape.omega_slope * (omega - shape.omega_centre))) - 1.0;
}
double progress_term(double lambda_ratio) { return 0.5 * (1.0 - lambda_ratio); }
double effort_term(double rotation) { return -0.2 * std::abs(rotation); }
}  // namespace

double navigation_reward(double omega, double lambda_ratio, double action, const RewardShape& shape) {
  const double orientation = orientation_term(omega, shape);
  const double progress = progress_term(lambda_ratio);
  const double effort = effort_term(action);
  return orientation + progress + effort;
}

double push_pull_reward(double omega, double omega_before, double lambda_ratio, double rotation, double new_depth,
                        bool in_wrong_branch, double wrong_branch_cost, double time_cost, const RewardShape& shape) {
  const double forward = std::clamp(new_depth, 0.0, 1.0);
  const double aim_paid =
      orientation_term(omega, shape) - orientation_term(omega_before, shape) + forward * progress_term(lambda_ratio);
  return aim_paid + effort_term(rotation) - (in_wrong_branch ? wrong_branch_cost : 0.0) - time_cost;
}

RewardProgress parse_reward_progress(const std::string& text) {
  if (text == "commanded") return RewardProgress::kCommanded;
  if (text == "course") return RewardProgress::kCourse;
  throw std::invalid_argument("reward progress '" + text + "' is not one of commanded, course");
}

const char* reward_progress_name(RewardProgress progress) {
  return progress == RewardProgress::kCourse ? "course" : "commanded";
}

}  // namespace gw
