// Task settings as JSON (task/task_config_json.hpp): a round trip gives the same settings, a partial object
// changes only its keys, and every bad input is refused naming its key.
#include <catch2/catch.hpp>

#include "task/task_config_json.hpp"

namespace {

// A TaskConfig with every field away from its default, valid for check_task_config.
gw::TaskConfig changed_config() {
  gw::TaskConfig c;
  c.dt_s = 0.005;
  c.frame_skip = 3;
  c.push_mm_per_s = 7.5;
  c.max_rotation_rad_per_s = 3.0;
  c.initial_insertion_mm = 3.0;
  c.max_start_tilt_rad = 0.2;
  c.action = gw::ActionLayout::kRotationInsertion;
  // every observation field away from its default: valid keys, but no layout has them together
  c.observation = {gw::OmegaPlane::kCorrectBranch, false, gw::JunctionModel::kCombined, true, true};
  c.tip_sample_spacing_mm = 1.5;
  c.lookahead_mm = 5.0;
  c.branch_direction_mm = 7.0;
  c.max_abs_speed_ratio = 4.0;
  c.max_lambda_ratio = 3.0;
  c.reward.omega_centre = 0.3;
  c.reward.omega_slope = 4.0;
  c.success_radius_mm = 3.0;
  c.wrong_branch_depth_mm = 5.0;
  c.control_radius_mm = 15.0;
  c.task_scale = gw::TaskScale::kVessel;
  c.wide_vessel_radius_mm = 5.0;
  c.intermediate_target_mm = 40.0;
  c.control_mode = gw::ControlMode::kAlways;
  c.max_steps = 321;
  c.max_steps_path_factor = 2.0;
  c.stuck_steps = 50;
  c.stuck_progress_mm = 2.0;
  c.wire_reserve_mm = 6.0;
  c.recovery_attempts = 2;
  c.recovery_retract_mm = 18.0;
  c.recovery_pull_mm_per_s = 8.0;
  c.recovery_turn_rad = 1.0;
  c.recovery_time_s = 20.0;
  c.recovery_assist = true;
  c.reward_wrong_branch = 2.0;
  c.reward_time_per_step = 0.5;
  c.reward_force_per_N = 0.75;
  c.force_limit_N = 1.25;
  c.close_junction_diameters = 3.0;
  c.reward.progress = gw::RewardProgress::kCourse;
  return c;
}

}  // namespace

TEST_CASE("task JSON: a round trip keeps every field, and every field is written") {
  const gw::TaskConfig changed = changed_config();
  const nlohmann::json j = gw::task_config_to_json(changed);
  CHECK(j.at("format") == gw::kTaskFormat);
  // Read into the defaults, the JSON gives `changed` back: every field changed above is written and read.
  const gw::TaskConfig back = gw::task_config_from_json(j, {}, /*check=*/false);  // `changed` is no layout
  CHECK(gw::task_config_to_json(back) == j);
  // ... and it differs from the defaults' JSON in every key but "format": no field is left out of the writer.
  const nlohmann::json defaults = gw::task_config_to_json(gw::TaskConfig{});
  REQUIRE(defaults.size() == j.size());
  for (const auto& [key, value] : j.items()) {
    INFO(key);
    if (key == "format") continue;
    CHECK(defaults.at(key) != value);
  }
  for (const auto& [key, value] : j.at("observation").items()) {
    INFO("observation." << key);  // tip_force is written only when true (obs/8), so the defaults lack it
    CHECK(defaults.at("observation").value(key, nlohmann::json()) != value);
  }
  for (const auto& [key, value] : j.at("reward").items()) {
    INFO("reward." << key);  // progress is written only when not "commanded", so the defaults lack it
    CHECK(defaults.at("reward").value(key, nlohmann::json()) != value);
  }
  CHECK(j.at("reward").at("progress") == "course");
}

TEST_CASE("task JSON: a partial object changes only its keys, and the observation may be a layout name") {
  const gw::TaskConfig base = changed_config();
  const gw::TaskConfig c =
      gw::task_config_from_json({{"push_mm_per_s", 12.0}, {"reward", {{"omega_slope", 6.0}}}}, base, /*check=*/false);
  CHECK(c.push_mm_per_s == 12.0);
  CHECK(c.reward.omega_slope == 6.0);
  CHECK(c.reward.omega_centre == base.reward.omega_centre);
  CHECK(c.frame_skip == base.frame_skip);
  const gw::TaskConfig paper =
      gw::task_config_from_json({{"observation", "guidewire-nav/obs/1"}, {"reward", {{"omega_centre", 0.1}}}});
  CHECK(std::string(paper.observation.name()) == "guidewire-nav/obs/1");
  CHECK(paper.reward.omega_centre == 0.1);
  const gw::TaskConfig kway = gw::task_config_from_json({{"observation", {{"junctions", "kway"}}}});
  CHECK(kway.observation.junctions == gw::JunctionModel::kKWay);
  CHECK(kway.observation.omega_side == gw::TaskConfig{}.observation.omega_side);
  const gw::TaskConfig generalist = gw::task_config_from_json(
      {{"action", "guidewire-nav/act/2"}, {"observation", "guidewire-nav/obs/8"}});
  CHECK(generalist.observation.tip_force);
  CHECK(gw::task_config_to_json(generalist)["observation"]["tip_force"] == true);
  CHECK_FALSE(gw::task_config_to_json(gw::TaskConfig{})["observation"].contains("tip_force"));
}

TEST_CASE("task JSON: the defaults are the shipped rotation actor's task (obs/3, act/1, its reward sigmoid)") {
  const gw::TaskConfig d;
  CHECK(std::string(d.observation.name()) == "guidewire-nav/obs/3");
  CHECK(d.action == gw::ActionLayout::kRotation);
  CHECK(d.reward.omega_centre == -0.5);
  CHECK(d.reward.omega_slope == 8.0);
  // the push/pull actor's time cost, read only under act/2
  CHECK(d.reward_time_per_step == 0.25);
  // the paper's task otherwise: strict, no force limit, no robustness extras
  CHECK(d.recovery_attempts == 0);
  CHECK(d.force_limit_N == 0.0);
}

TEST_CASE("task JSON: bad input is refused naming the key") {
  using Catch::Matchers::Contains;
  auto refused = [](const nlohmann::json& j) {
    try {
      gw::task_config_from_json(j);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refused({{"push_speed", 10.0}}), Contains("\"push_speed\" is not a task setting"));
  CHECK_THAT(refused({{"observation", {{"omega_sides", true}}}}), Contains("\"observation.omega_sides\" is not"));
  CHECK_THAT(refused({{"reward", {{"centre", 0.0}}}}), Contains("\"reward.centre\" is not"));
  CHECK_THAT(refused({{"reward", {{"progress", "depth"}}}}), Contains("\"reward.progress\""));
  CHECK_THAT(refused({{"reward", {{"progress", 1}}}}), Contains("\"reward.progress\" must be a string"));
  CHECK_THAT(refused({{"push_mm_per_s", "fast"}}), Contains("\"push_mm_per_s\" must be a number"));
  CHECK_THAT(refused({{"frame_skip", 2.5}}), Contains("\"frame_skip\" must be an integer"));
  CHECK_THAT(refused({{"recovery_assist", 1}}), Contains("\"recovery_assist\" must be true or false"));
  CHECK_THAT(refused({{"action", "guidewire-nav/act/9"}}), Contains("\"action\""));
  CHECK_THAT(refused({{"task_scale", "big"}}), Contains("\"task_scale\""));
  CHECK_THAT(refused({{"observation", "guidewire-nav/obs/99"}}), Contains("\"observation\""));
  CHECK_THAT(refused({{"observation", "guidewire-nav/obs/7"}}), Contains("is not one of"));  // retired
  CHECK_THAT(refused({{"roll_disturbance_probability", 0.5}}), Contains("is not a task setting"));  // retired
  CHECK_THAT(refused({{"format", "guidewire-nav/task/0"}}), Contains("\"format\""));
  CHECK_THAT(refused(nlohmann::json::array()), Contains("must be a JSON object"));
  // valid keys, an invalid combination: the check names the field
  CHECK_THAT(refused({{"push_mm_per_s", -1.0}}), Contains("push_mm_per_s"));
  CHECK_THAT(refused({{"recovery_assist", true}}), Contains("--recovery K"));
  CHECK_THAT(refused({{"observation", {{"omega_plane", "correct_branch"}}}}), Contains("omega_side"));
}
