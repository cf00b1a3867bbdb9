// The push/pull task (issue 37 item 1b, docs/recovery.md): action layout act/2 (rotation, insertion) with
// observation obs/5. At insertion +1 it is the paper's episode; stopping holds the wire and is no stall;
// the wire is never pulled out past its start; with recovery the actor pulls out of a wrong child itself and
// its (K+1)-th entry ends the procedure. An act/2 actor's JSON sets the task's layouts.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "lib/runner/controller.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "lib/runner/run_episode.hpp"
#include "task/episode.hpp"
#include "task/navigation_task.hpp"
#include "task/observation.hpp"
#include "task/reward.hpp"
#include "engine/wire/wire_params.hpp"
#include "tests/runner/aim_controllers.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kT1 = std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y";

gw::NavigationTask t1_task(bool push_pull, int recovery_attempts) {
  static const gw::NavigationAnatomy nav =
      gw::load_navigation_anatomy(kT1 + ".stl", {1.0, std::nullopt, kT1 + ".truth.json", false});
  gw::TaskConfig c;
  c.observation.omega_side = true;
  if (push_pull) {
    c.action = gw::ActionLayout::kRotationInsertion;
    c.observation.push_pull = true;
  }
  c.recovery_attempts = recovery_attempts;
  return gw::make_navigation_task(c, gw::default_wire_params(), {nav.anatomy});
}

}  // namespace

TEST_CASE("push/pull: insertion +1 is the paper's episode bit for bit", "[runner][push_pull]") {
  const gw::NavigationTask paper = t1_task(false, 0), push_pull = t1_task(true, 0);
  for (const bool at_wrong : {false, true}) {
    gw::EpisodeState a = gw::reset_episode(paper, 0, 1, 7), b = gw::reset_episode(push_pull, 0, 1, 7);
    int steps = 0;
    const gw::RewardShape shape = push_pull.config.reward;
    auto orientation = [&shape](double w) { return 2.0 / (1.0 + std::exp(shape.omega_slope * (w - shape.omega_centre))) - 1.0; };
    for (;;) {
      const double omega_before = b.obs[gw::obs_index::kOmega];
      const double rotation = gwtest::aim_rotation(a.obs, at_wrong);
      const gw::StepOutcome oa = gw::step_episode(paper, a, rotation);
      const gw::StepOutcome ob = gw::step_episode(push_pull, b, gw::Action{rotation, 1.0});
      ++steps;
      REQUIRE(a.tip == b.tip);
      for (int i = 0; i < gw::kSideObservationSize; ++i) REQUIRE(oa.obs[i] == ob.obs[i]);
      REQUIRE(ob.obs[gw::obs_index::kInsertion] == 1.0);
      REQUIRE(oa.terminated == ob.terminated);
      REQUIRE(oa.truncated == ob.truncated);
      // reward.hpp: at insertion 1 outside a wrong child, Eq. 3 with the aim paid by its change, less the time cost
      if (!oa.info.wrong_branch)
        REQUIRE(ob.reward ==
                Approx(oa.reward - orientation(omega_before) - push_pull.config.reward_time_per_step).margin(1e-9));
      if (oa.terminated || oa.truncated) {
        CHECK(oa.info.success == !at_wrong);
        CHECK(ob.info.wrong_branch == at_wrong);
        CHECK(ob.obs[gw::obs_index::kWrongBranch] == (at_wrong ? 1.0 : 0.0));
        break;
      }
    }
    CHECK(steps > 50);
  }
}

TEST_CASE("push/pull: stopping holds the wire and is no stall, pulling stops at the start insertion",
          "[runner][push_pull]") {
  const gw::NavigationTask task = t1_task(true, 0);
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 3);
  for (int k = 0; k < 20; ++k) gw::step_episode(task, s, gw::Action{0.0, 1.0});
  const double inserted = s.wire.inserted_length_mm;
  // Three times the strict stall's 60 steps without pushing: no stall, the wire stays; stopping earns no progress,
  // only the aim's change, less the rotation's effort and the time cost (reward.hpp).
  const gw::TaskConfig& c = task.config;
  auto orientation = [&c](double w) {
    return 2.0 / (1.0 + std::exp(c.reward.omega_slope * (w - c.reward.omega_centre))) - 1.0;
  };
  auto step = [&](const gw::Action& act, double& aim_change) {
    const double before = s.obs[gw::obs_index::kOmega];
    const gw::StepOutcome out = gw::step_episode(task, s, act);
    aim_change = orientation(out.obs[gw::obs_index::kOmega]) - orientation(before);
    return out;
  };
  double aim = 0.0;
  for (int k = 0; k < 3 * c.stuck_steps; ++k) {
    const gw::StepOutcome out = step(gw::Action{0.3, 0.0}, aim);
    REQUIRE_FALSE(out.truncated);
    REQUIRE_FALSE(out.terminated);
    REQUIRE(out.reward == Approx(aim - 0.2 * 0.3 - c.reward_time_per_step).margin(1e-12));
    REQUIRE(out.obs[gw::obs_index::kInsertion] == 0.0);
  }
  CHECK(s.wire.inserted_length_mm == Approx(inserted).margin(1e-9));
  // Back and forth earns no progress: 5 steps back, 5 steps in again reach no new depth; the step after does.
  for (int k = 0; k < 10; ++k) {
    const gw::StepOutcome out = step(gw::Action{0.0, k < 5 ? -1.0 : 1.0}, aim);
    REQUIRE(out.reward == Approx(aim - c.reward_time_per_step).margin(1e-12));
  }
  const gw::StepOutcome deeper = step(gw::Action{0.0, 1.0}, aim);
  CHECK(deeper.reward == Approx(aim + 0.5 * (1.0 - deeper.obs[gw::obs_index::kLambda]) - c.reward_time_per_step)
                             .margin(1e-12));
  // Pulling: back to the start insertion and no further (the command is then 0).
  for (int k = 0; k < 100; ++k) gw::step_episode(task, s, gw::Action{0.0, -1.0});
  CHECK(s.wire.inserted_length_mm >= task.config.initial_insertion_mm - 1e-9);
  CHECK(s.wire.inserted_length_mm < task.config.initial_insertion_mm + 0.5);
  CHECK(s.obs[gw::obs_index::kInsertion] == 0.0);
  CHECK_FALSE(s.done);
  CHECK_THROWS_WITH(gw::step_episode(task, s, gw::Action{0.0, std::nan("")}), Catch::Contains("insertion"));
}

TEST_CASE("push/pull: a time cost comes off every step, stopped or moving, and nothing else changes",
          "[runner][push_pull]") {
  gw::NavigationTask plain = t1_task(true, 0), costly = t1_task(true, 0);
  plain.config.reward_time_per_step = 0.0;  // the first push/pull run's reward
  costly.config.reward_time_per_step = 0.25;  // the shipped push/pull actor's (the default)
  gw::EpisodeState a = gw::reset_episode(plain, 0, 1, 3), b = gw::reset_episode(costly, 0, 1, 3);
  for (int k = 0; k < 40; ++k) {
    const gw::Action act{0.3, k < 10 ? 1.0 : (k < 25 ? 0.0 : 1.0)};  // push, stop, push on
    const gw::StepOutcome oa = gw::step_episode(plain, a, act), ob = gw::step_episode(costly, b, act);
    REQUIRE(a.tip == b.tip);
    REQUIRE(ob.reward == Approx(oa.reward - 0.25).margin(1e-12));
  }
  costly.config.reward_time_per_step = -1.0;
  CHECK_THROWS_WITH(gw::check_task_config(costly.config), Catch::Contains("reward_time_per_step"));
}

TEST_CASE("push/pull: the aim is paid by its change over the step, whatever the wire does, and progress by new depth",
          "[runner][push_pull]") {
  gw::NavigationTask task = t1_task(true, 0);
  const gw::TaskConfig& c = task.config;
  auto orientation = [&c](double w) {
    return 2.0 / (1.0 + std::exp(c.reward.omega_slope * (w - c.reward.omega_centre))) - 1.0;
  };
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 3);
  double omega_before = s.obs[gw::obs_index::kOmega];
  for (int k = 0; k < 40; ++k) {
    const gw::Action act{0.3, k < 10 ? 1.0 : (k < 25 ? 0.0 : 1.0)};  // push (new depth 1), stop (0), push on
    const gw::StepOutcome out = gw::step_episode(task, s, act);
    const double omega = out.obs[gw::obs_index::kOmega];
    const double progress = 0.5 * (1.0 - out.obs[gw::obs_index::kLambda]);
    const double rest = -0.2 * 0.3 - c.reward_time_per_step;
    if (k < 10)  // new depth 1: the aim's change and the progress term
      REQUIRE(out.reward == Approx(orientation(omega) - orientation(omega_before) + progress + rest).margin(1e-9));
    else if (k < 25)  // stopped: no new depth, the aim's change only
      REQUIRE(out.reward == Approx(orientation(omega) - orientation(omega_before) + rest).margin(1e-9));
    omega_before = omega;
  }
}

TEST_CASE("push/pull: a stall is wire pushed in without progress", "[runner][push_pull]") {
  // With a retry left the procedure goes on in the wrong child; pushing on along it at a third of the speed
  // makes no progress along the course, and the stall comes after 24 mm of wire pushed in: three times the
  // strict rule's 60 steps.
  const gw::NavigationTask task = t1_task(true, 1);
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 3);
  const double stall_mm = task.config.stuck_steps * task.config.frame_skip * task.config.dt_s * task.config.push_mm_per_s;
  CHECK(stall_mm == Approx(24.0));
  gw::StepOutcome out;
  int steps = 0;
  do {
    out = gw::step_episode(task, s, gw::Action{gwtest::aim_rotation(s.obs, true), 1.0 / 3.0});
    ++steps;
  } while (!s.done && steps < 5000);
  REQUIRE(s.done);
  REQUIRE(out.info.stuck);
  CHECK(out.truncated);
  CHECK(s.wire.inserted_length_mm - s.stall.inserted_at_best_mm >= stall_mm);
  CHECK(s.wire.inserted_length_mm - s.stall.inserted_at_best_mm < stall_mm + 0.2);
  CHECK(s.steps - s.stall.best_progress_step >= 3 * task.config.stuck_steps - 1);
}

TEST_CASE("push/pull with recovery: the actor pulls out of a wrong child itself, the (K+1)-th entry ends it",
          "[runner][push_pull]") {
  const gw::NavigationTask task = t1_task(true, 1);
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 5);
  gw::StepOutcome out;
  // 1. Into the wrong child: the strict episode ends there, the procedure goes on.
  double omega_before = s.obs[gw::obs_index::kOmega];
  do {
    omega_before = s.obs[gw::obs_index::kOmega];
    out = gw::step_episode(task, s, gw::Action{gwtest::aim_rotation(s.obs, true), 1.0});
  } while (!out.info.strict_end && !s.done);
  REQUIRE(out.info.strict_end);
  REQUIRE(out.info.wrong_branch);
  CHECK_FALSE(out.terminated);
  CHECK_FALSE(out.truncated);
  CHECK(out.info.recovery_attempts == 1);
  CHECK(out.obs[gw::obs_index::kWrongBranch] == 1.0);
  CHECK(out.info.in_control);
  // In the wrong child the step costs reward_wrong_branch more than the push/pull reward without it.
  const double without = gw::push_pull_reward(out.obs[gw::obs_index::kOmega], omega_before, out.obs[gw::obs_index::kLambda],
                                              out.obs[gw::obs_index::kAction], 1.0, false, 0.0,
                                              task.config.reward_time_per_step, task.config.reward);
  CHECK(out.reward == Approx(without - task.config.reward_wrong_branch));
  // 2. Pull back until the tip is out of it (bounded).
  int pulled = 0;
  while (s.obs[gw::obs_index::kWrongBranch] == 1.0 && pulled < 200) {
    out = gw::step_episode(task, s, gw::Action{0.0, -1.0});
    REQUIRE_FALSE(s.done);
    ++pulled;
  }
  REQUIRE(s.obs[gw::obs_index::kWrongBranch] == 0.0);
  CHECK(pulled >= 1);  // the test says "in" from wrong_branch_depth_mm into the child: a pull of 0.4 mm can end it
  for (int k = 0; k < 10; ++k) out = gw::step_episode(task, s, gw::Action{0.0, -1.0});
  // 3. In again: the second entry is past K = 1 retries and ends the procedure as a failure.
  do out = gw::step_episode(task, s, gw::Action{gwtest::aim_rotation(s.obs, true), 1.0});
  while (!s.done);
  CHECK(out.terminated);
  CHECK(out.info.wrong_branch);
  CHECK(out.info.recovery_attempts == 1);
  CHECK_FALSE(out.info.strict_end);
}

TEST_CASE("push/pull: an act/2 actor sets the task's layouts and its insertion reaches the task", "[runner][push_pull]") {
  const fs::path dir = fs::path(GW_BINARY_DIR) / "test_runner_scratch" / "push_pull";
  fs::create_directories(dir);
  // A linear actor: rotation = tanh(0), insertion = tanh(0.5 + wrong_branch entry * -2).
  auto write = [&](const std::string& obs_layout, int obs, const std::string& action_layout, int actions) {
    std::string w;
    for (int r = 0; r < actions; ++r)
      for (int i = 0; i < obs; ++i) w += std::string(w.empty() ? "" : ", ") + (r == 1 && i == obs - 1 ? "-2" : "0");
    const std::string bias = actions == 2 ? "0, 0.5" : "0";
    const std::string bounds = actions == 2 ? "[-1, -1]" : "[-1]", high = actions == 2 ? "[1, 1]" : "[1]";
    const fs::path p = dir / ("actor_" + std::to_string(obs) + "_" + std::to_string(actions) + ".json");
    std::ofstream(p) << R"({"format": "guidewire-nav/actor/1", "obs_size": )" << obs << R"(, "action_size": )" << actions
                     << R"(, "obs_layout": ")" << obs_layout << R"(", "action_layout": ")" << action_layout
                     << R"(", "obs_normalization": null, "layers": [{"shape": [)" << actions << ", " << obs
                     << R"(], "weight": [)" << w << R"(], "bias": [)" << bias
                     << R"(], "activation": "identity"}], "output": {"squash": "tanh", "low": )" << bounds
                     << R"(, "high": )" << high << "}}";
    return p.string();
  };
  gw::TaskConfig config;
  const auto actor = gw::make_controller("policy", write("guidewire-nav/obs/5", 14, "guidewire-nav/act/2", 2));
  actor->adapt(config);
  CHECK(config.action == gw::ActionLayout::kRotationInsertion);
  CHECK(config.observation.push_pull);
  CHECK(std::string(config.observation.name()) == "guidewire-nav/obs/5");
  gw::Observation obs{};
  CHECK(actor->act(obs).insertion == Approx(std::tanh(0.5)).epsilon(1e-6));
  obs[gw::obs_index::kWrongBranch] = 1.0;
  CHECK(actor->act(obs).insertion == Approx(std::tanh(-1.5)).epsilon(1e-6));
  // Back to a rotation-only actor: its layouts again.
  gw::make_controller("scripted-omega", "")->adapt(config);  // baselines leave the config alone
  CHECK(config.action == gw::ActionLayout::kRotationInsertion);
  CHECK_THROWS_WITH(gw::make_controller("policy", write("guidewire-nav/obs/7", 15, "guidewire-nav/act/2", 2)),
                    Catch::Contains("unknown observation"));  // obs/7 is retired (docs/policy_history.md)
  // Layouts that do not go together, or sizes that are not the layout's, are refused by name.
  CHECK_THROWS_WITH(gw::make_controller("policy", write("guidewire-nav/obs/5", 14, "guidewire-nav/act/1", 1)),
                    Catch::Contains("obs/5 and obs/8 go with act/2"));
  CHECK_THROWS_WITH(gw::make_controller("policy", write("guidewire-nav/obs/3", 12, "guidewire-nav/act/2", 2)),
                    Catch::Contains("obs/5 and obs/8 go with act/2"));
  CHECK_THROWS_WITH(gw::make_controller("policy", write("guidewire-nav/obs/5", 14, "guidewire-nav/act/2", 1)),
                    Catch::Contains("outputs 1") && Catch::Contains("has 2"));
  CHECK_THROWS_WITH(gw::make_controller("policy", write("guidewire-nav/obs/5", 14, "guidewire-nav/act/9", 2)),
                    Catch::Contains("unknown action") && Catch::Contains("guidewire-nav/act/2"));
  // A task with act/2 and a rotation-only observation (or the reverse) is refused.
  gw::TaskConfig bad;
  bad.action = gw::ActionLayout::kRotationInsertion;
  CHECK_THROWS_WITH(gw::check_task_config(bad), Catch::Contains("obs/5"));
}

TEST_CASE("push/pull: the shipped push/pull actor runs an episode end to end, the same twice", "[runner][push_pull]") {
  const std::string path = std::string(GW_SOURCE_DIR) + "/policy/trained/sac_actor_push_pull.json";
  gw::TaskConfig config;
  auto actor = gw::make_controller("policy", path);
  actor->adapt(config);
  REQUIRE(config.action == gw::ActionLayout::kRotationInsertion);
  config.recovery_attempts = 3;
  static const gw::NavigationAnatomy nav =
      gw::load_navigation_anatomy(kT1 + ".stl", {1.0, std::nullopt, kT1 + ".truth.json", false});
  const gw::NavigationTask task = gw::make_navigation_task(config, gw::default_wire_params(), {nav.anatomy});
  const gw::EpisodeTrace a = gw::run_episode(task, 0, 2, 11, *actor);
  const gw::EpisodeTrace b = gw::run_episode(task, 0, 2, 11, *gw::make_controller("policy", path));
  REQUIRE(a.insertion.size() == a.action.size());
  CHECK(a.observation_names.size() == 14);
  CHECK(a.recovery_attempts_allowed == 3);
  CHECK(!a.recovery_outcome.empty());
  CHECK(a.tip == b.tip);
  CHECK(a.insertion == b.insertion);
  // The actor sets the speed: somewhere it is not the constant push.
  bool varied = false;
  for (std::size_t f = 1; f < a.insertion.size(); ++f) varied = varied || (a.agent_in_control[f] && a.insertion[f] != 1.0);
  CHECK(varied);
}

TEST_CASE("push/pull, progress along the course: a push into a wrong child earns less, and after pulling out of it "
          "the correct child pays before the commands are back at their deepest",
          "[runner][push_pull]") {
  gw::NavigationTask commanded = t1_task(true, 1), course = t1_task(true, 1);
  course.config.reward.progress = gw::RewardProgress::kCourse;
  const gw::TaskConfig& c = course.config;
  const double step_mm = c.frame_skip * c.dt_s * c.push_mm_per_s;
  gw::EpisodeState a = gw::reset_episode(commanded, 0, 1, 5), b = gw::reset_episode(course, 0, 1, 5);
  double deepest = b.progress_mm, paid_commanded = 0.0, paid_course = 0.0;
  // The progress term each step paid, from the reward: what is left once the other terms are taken off.
  auto progress_paid = [&c](const gw::StepOutcome& out, double omega_before, bool wrong) {
    return out.reward - gw::push_pull_reward(out.obs[gw::obs_index::kOmega], omega_before,
                                             out.obs[gw::obs_index::kLambda], out.obs[gw::obs_index::kAction], 0.0,
                                             wrong, c.reward_wrong_branch, c.reward_time_per_step, c.reward);
  };
  auto step = [&](const gw::Action& act) {
    const double omega_before = a.obs[gw::obs_index::kOmega];
    const gw::StepOutcome oa = gw::step_episode(commanded, a, act), ob = gw::step_episode(course, b, act);
    REQUIRE(a.tip == b.tip);  // the reward changes nothing else
    const bool wrong = ob.obs[gw::obs_index::kWrongBranch] > 0;
    const double lambda_term = 0.5 * (1.0 - ob.obs[gw::obs_index::kLambda]);
    const double forward = std::clamp((b.progress_mm - deepest) / step_mm, 0.0, 1.0);
    deepest = std::max(deepest, b.progress_mm);
    REQUIRE(progress_paid(ob, omega_before, wrong) == Approx(forward * lambda_term).margin(1e-9));
    paid_commanded += progress_paid(oa, omega_before, wrong);
    paid_course += progress_paid(ob, omega_before, wrong);
    return ob;
  };
  // 1. Aimed into the wrong child and pushed until the tip is in it.
  gw::StepOutcome out;
  do out = step(gw::Action{gwtest::aim_rotation(b.obs, true), 1.0});
  while (!out.info.strict_end && !b.done);
  REQUIRE(out.info.wrong_branch);
  for (int k = 0; k < 10 && !b.done; ++k) out = step(gw::Action{0.0, 1.0});
  REQUIRE_FALSE(b.done);
  CHECK(paid_course < paid_commanded);
  // 2. Out of it again and ten steps further, then aimed at the correct child and pushed: under kCommanded the
  // progress term pays only once the commands are back where they went, under kCourse as soon as the tip is deeper
  // along the course than ever (past the fork).
  int pulled = 0;
  while ((b.obs[gw::obs_index::kWrongBranch] > 0 || pulled < 10) && pulled < 200) {
    out = step(gw::Action{0.0, -1.0});
    pulled += b.obs[gw::obs_index::kWrongBranch] > 0 ? 0 : 1;
  }
  REQUIRE(b.obs[gw::obs_index::kWrongBranch] == 0.0);
  int first_commanded = -1, first_course = -1;
  for (int k = 0; k < 300 && !b.done && first_commanded < 0; ++k) {
    const double before_commanded = paid_commanded, before_course = paid_course;
    out = step(gw::Action{gwtest::aim_rotation(b.obs, false), 1.0});
    if (first_course < 0 && paid_course > before_course + 1e-12) first_course = k;
    if (paid_commanded > before_commanded + 1e-12) first_commanded = k;
  }
  INFO("first paid step after the pull-back: commanded " << first_commanded << ", course " << first_course);
  REQUIRE(first_course >= 0);
  CHECK((first_commanded < 0 || first_course < first_commanded));
}
