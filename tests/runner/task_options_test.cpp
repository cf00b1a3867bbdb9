// The task settings' command line (lib/runner/task_options.hpp): --task then the flags, in that order, one
// surface for navigate, evaluate and guidewire-server.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>

#include "lib/runner/task_options.hpp"
#include "task/task_config_json.hpp"

namespace {

gw::TaskConfig parse(std::vector<std::string> args) {
  CLI::App app{"test"};
  gw::TaskOptions options;
  gw::add_task_options(app, options);
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments in reverse order
  app.parse(args);
  return gw::resolve_task_config(options);
}

}  // namespace

TEST_CASE("task options: no flag gives the defaults, and each flag sets its field") {
  CHECK(gw::task_config_to_json(parse({})) == gw::task_config_to_json(gw::TaskConfig{}));
  const gw::TaskConfig c = parse({"--push-speed", "5", "--recovery", "3", "--recovery-assist", "--recovery-turn", "90",
                                  "--force-limit", "1.5", "--junctions", "kway", "--task-scale", "vessel",
                                  "--control", "always", "--intermediate-target", "0"});
  CHECK(c.push_mm_per_s == 5.0);
  CHECK(c.recovery_attempts == 3);
  CHECK(c.recovery_assist);
  CHECK(c.recovery_turn_rad == Approx(1.5707963267948966));
  CHECK(c.force_limit_N == 1.5);
  CHECK(c.observation.junctions == gw::JunctionModel::kKWay);
  CHECK(c.observation.omega_side);  // --junctions leaves the rest of the observation as it was
  CHECK(c.task_scale == gw::TaskScale::kVessel);
  CHECK(c.control_mode == gw::ControlMode::kAlways);
  CHECK(c.intermediate_target_mm == 0.0);
  const gw::TaskConfig paper = parse({"--omega-plane", "correct_branch"});
  CHECK(std::string(paper.observation.name()) == "guidewire-nav/obs/1");
  const gw::TaskConfig push_pull = parse({"--push-pull", "--junctions", "separate"});
  CHECK(std::string(push_pull.observation.name()) == "guidewire-nav/obs/5");
  CHECK(push_pull.action == gw::ActionLayout::kRotationInsertion);
}

TEST_CASE("task options: --task (a file or inline JSON) first, the flags over it") {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "gw_task_options_test.json";
  std::ofstream(file) << R"({"push_mm_per_s": 6.0, "recovery_attempts": 2, "reward": {"omega_centre": 0.1}})";
  const gw::TaskConfig from_file = parse({"--task", file.string()});
  CHECK(from_file.push_mm_per_s == 6.0);
  CHECK(from_file.recovery_attempts == 2);
  CHECK(from_file.reward.omega_centre == 0.1);
  const gw::TaskConfig flag_wins = parse({"--task", file.string(), "--push-speed", "8"});
  CHECK(flag_wins.push_mm_per_s == 8.0);
  CHECK(flag_wins.recovery_attempts == 2);
  const gw::TaskConfig inline_json = parse({"--task", R"({"force_limit_N": 2.0})"});
  CHECK(inline_json.force_limit_N == 2.0);
  std::filesystem::remove(file);
}

TEST_CASE("task options: a bad --task or flag is one clear error naming it") {
  using Catch::Matchers::Contains;
  auto error = [](std::vector<std::string> args) {
    try {
      parse(std::move(args));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(error({"--task", "/nonexistent/task.json"}), Contains("--task: /nonexistent/task.json: cannot read"));
  CHECK_THAT(error({"--task", "{not json"}), Contains("--task: not JSON"));
  CHECK_THAT(error({"--task", R"({"push_speed": 1})"}), Contains("\"push_speed\" is not a task setting"));
  CHECK_THAT(error({"--recovery-assist"}), Contains("--recovery K"));
  CHECK_THAT(error({"--junctions", "many"}), Contains("junction model 'many'"));
}
