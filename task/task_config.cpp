#include "task/task_config.hpp"

#include <cmath>
#include <stdexcept>

namespace gw {

namespace {
void require(bool ok, const char* field, const char* rule) {
  if (!ok) throw std::invalid_argument(std::string("task config: ") + field + " must be " + rule);
}
}  // namespace

void check_task_config(const TaskConfig& c) {
  require(c.dt_s > 0 && std::isfinite(c.dt_s), "dt_s", "> 0");
  require(c.frame_skip >= 1, "frame_skip", ">= 1");
  require(c.push_mm_per_s > 0 && std::isfinite(c.push_mm_per_s), "push_mm_per_s", "> 0");
  require(c.max_rotation_rad_per_s >= 0 && std::isfinite(c.max_rotation_rad_per_s), "max_rotation_rad_per_s", ">= 0");
  require(c.initial_insertion_mm > 0, "initial_insertion_mm", "> 0");
  require(c.max_start_tilt_rad >= 0 && c.max_start_tilt_rad < 1.5, "max_start_tilt_rad", "in [0, 1.5)");
  require(c.tip_sample_spacing_mm > 0, "tip_sample_spacing_mm", "> 0");
  require(c.lookahead_mm >= 0, "lookahead_mm", ">= 0");
  require(c.branch_direction_mm > 0, "branch_direction_mm", "> 0");
  require(c.max_abs_speed_ratio > 0, "max_abs_speed_ratio", "> 0");
  require(c.max_lambda_ratio >= 1, "max_lambda_ratio", ">= 1");
  require(std::isfinite(c.reward.omega_centre) && std::abs(c.reward.omega_centre) <= 1, "reward.omega_centre",
          "in [-1, 1]");
  require(c.reward.omega_slope > 0 && c.reward.omega_slope <= 50, "reward.omega_slope", "in (0, 50]");
  require(c.success_radius_mm > 0, "success_radius_mm", "> 0");
  require(c.wrong_branch_depth_mm >= 0, "wrong_branch_depth_mm", ">= 0");
  require(c.control_radius_mm > 0, "control_radius_mm", "> 0");
  require(c.wide_vessel_radius_mm > 0 && std::isfinite(c.wide_vessel_radius_mm), "wide_vessel_radius_mm", "> 0");
  require(c.intermediate_target_mm >= 0, "intermediate_target_mm", ">= 0");
  require(c.max_steps >= 0, "max_steps", ">= 0 (0 = automatic)");
  require(c.max_steps_path_factor >= 1, "max_steps_path_factor", ">= 1");
  require(c.stuck_steps >= 1, "stuck_steps", ">= 1");
  require(c.stuck_progress_mm >= 0, "stuck_progress_mm", ">= 0");
  require(c.wire_reserve_mm >= 0, "wire_reserve_mm", ">= 0");
  require(c.recovery_attempts >= 0, "recovery_attempts", ">= 0 (0 = the paper's strict task)");
  require(c.recovery_retract_mm > 0 && std::isfinite(c.recovery_retract_mm), "recovery_retract_mm", "> 0");
  require(c.recovery_pull_mm_per_s > 0 && std::isfinite(c.recovery_pull_mm_per_s), "recovery_pull_mm_per_s", "> 0");
  require(c.recovery_turn_rad >= 0 && c.recovery_turn_rad <= 6.283185307179586, "recovery_turn_rad", "in [0, 2 pi]");
  require(c.recovery_time_s >= 0 && std::isfinite(c.recovery_time_s), "recovery_time_s", ">= 0");
  require(c.recovery_turn_rad == 0 || c.recovery_attempts == 0 || c.max_rotation_rad_per_s > 0,
          "max_rotation_rad_per_s", "> 0 when recovery turns the wire");
  require(c.close_junction_diameters >= 0 && std::isfinite(c.close_junction_diameters), "close_junction_diameters",
          ">= 0");
  require(c.reward_wrong_branch >= 0 && std::isfinite(c.reward_wrong_branch), "reward_wrong_branch", ">= 0");
  require(c.reward_time_per_step >= 0 && std::isfinite(c.reward_time_per_step), "reward_time_per_step", ">= 0");
  require((c.action == ActionLayout::kRotationInsertion) == c.observation.push_pull, "observation",
          "obs/5 or obs/8 (with the insertion and wrong-branch entries) exactly when the action is act/2 (push/pull)");
  require(c.reward_force_per_N >= 0 && std::isfinite(c.reward_force_per_N), "reward_force_per_N", ">= 0 (0 = off)");
  require(!c.recovery_assist || c.recovery_attempts > 0, "recovery_assist (--recovery-assist)",
          "used with recovery_attempts > 0 (--recovery K: the assist pulls back within those K attempts)");
  require(c.force_limit_N >= 0 && std::isfinite(c.force_limit_N), "force_limit_N", ">= 0 (0 = off)");
}

ControlMode parse_control_mode(const std::string& text) {
  if (text == "always") return ControlMode::kAlways;
  if (text == "near_bifurcation") return ControlMode::kNearBifurcation;
  if (text == "auto") return ControlMode::kAuto;
  throw std::invalid_argument("control mode '" + text + "' is not one of always, near_bifurcation, auto");
}

const char* control_mode_name(ControlMode mode) {
  switch (mode) {
    case ControlMode::kAlways: return "always";
    case ControlMode::kNearBifurcation: return "near_bifurcation";
    case ControlMode::kAuto: return "auto";
  }
  return "auto";
}

TaskScale parse_task_scale(const std::string& text) {
  if (text == "fixed") return TaskScale::kFixed;
  if (text == "vessel") return TaskScale::kVessel;
  if (text == "auto") return TaskScale::kAuto;
  throw std::invalid_argument("task scale '" + text + "' is not one of fixed, vessel, auto");
}

const char* task_scale_name(TaskScale scale) {
  switch (scale) {
    case TaskScale::kFixed: return "fixed";
    case TaskScale::kVessel: return "vessel";
    case TaskScale::kAuto: return "auto";
  }
  return "auto";
}

}  // namespace gw
