// Episodes on a hand-made Y centerline in free space (no wall): reset, stepping, determinism,
// control zone, end conditions and bad input. Wall contact is exercised in tests/server on the
// training anatomies.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include "task/episode.hpp"
#include "task/reward.hpp"
#include "tests/task/hand_made_graphs.hpp"

using Approx = Catch::Detail::Approx;

namespace {

gw::NavigationTask free_space_task(const gw::CenterlineGraph& g, gw::TaskConfig config = {}) {
  std::vector<gw::Anatomy> anatomies;
  anatomies.push_back(gw::make_anatomy("y", g, nullptr));
  return gw::make_navigation_task(config, gw::default_wire_params(), std::move(anatomies));
}

bool same_bits(const gw::Observation& a, const gw::Observation& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

}  // namespace

TEST_CASE("reset: seeded start, observation in bounds, history equals present", "[task][episode]") {
  const gw::NavigationTask task = free_space_task(gwtest::y_graph());
  const gw::EpisodeState s = gw::reset_episode(task, 0, 1, 42);
  CHECK(s.target_id == 1);
  CHECK(s.steps == 0);
  CHECK(s.max_steps > 100);
  CHECK(s.start_tilt_rad <= task.config.max_start_tilt_rad);
  gw::Observation lo, hi;
  gw::observation_bounds(task.config, lo, hi);
  for (int i = 0; i < gw::kObservationSize; ++i) {
    CHECK(std::isfinite(s.obs[i]));
    CHECK(s.obs[i] >= lo[i]);
    CHECK(s.obs[i] <= hi[i]);
  }
  for (int i = 0; i < gw::kThetaCount; ++i) CHECK(s.obs[gw::obs_index::kThetaPrev + i] == s.obs[gw::obs_index::kTheta + i]);
  CHECK(s.obs[gw::obs_index::kLambda] == 1.0);
  CHECK(s.obs[gw::obs_index::kAction] == 0.0);
  // The wire starts along the inlet axis, tilted by at most 10 degrees: tip tangent . c ~ 1.
  CHECK(s.obs[gw::obs_index::kTheta + 2] > std::cos(task.config.max_start_tilt_rad) - 0.05);
  // Different seeds give different starts; the same seed the same one.
  const gw::EpisodeState s2 = gw::reset_episode(task, 0, 1, 43);
  CHECK(s2.start_rotation_rad != s.start_rotation_rad);
  CHECK(gw::reset_episode(task, 0, 1, 42).start_rotation_rad == s.start_rotation_rad);
  // Anatomy and target drawn from the seed when not given.
  bool seen[3] = {false, false, false};
  for (std::uint64_t seed = 0; seed < 40; ++seed) seen[gw::reset_episode(task, -1, 0, seed).target_id] = true;
  CHECK(seen[1]);
  CHECK(seen[2]);
}

TEST_CASE("reset refuses unknown anatomies and targets", "[task][episode]") {
  const gw::NavigationTask task = free_space_task(gwtest::y_graph());
  CHECK_THROWS_WITH(gw::reset_episode(task, 3, 1, 0), Catch::Contains("anatomy index 3"));
  CHECK_THROWS_WITH(gw::reset_episode(task, 0, 7, 0), Catch::Contains("valid targets are 1..2"));
}

TEST_CASE("stepping: same seed and actions give the same trajectory bit for bit", "[task][episode]") {
  const gw::NavigationTask task = free_space_task(gwtest::y_graph());
  auto run = [&](std::uint64_t seed) {
    gw::EpisodeState s = gw::reset_episode(task, 0, 2, seed);
    std::vector<gw::StepOutcome> outs;
    for (int k = 0; k < 40 && !s.done; ++k) outs.push_back(gw::step_episode(task, s, std::sin(0.3 * k)));
    return std::make_pair(outs, s);
  };
  const auto [a, sa] = run(7);
  const auto [b, sb] = run(7);
  REQUIRE(a.size() == b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    CHECK(same_bits(a[k].obs, b[k].obs));
    CHECK(std::memcmp(&a[k].reward, &b[k].reward, sizeof(double)) == 0);
  }
  REQUIRE(sa.wire.x.size() == sb.wire.x.size());
  for (size_t i = 0; i < sa.wire.x.size(); ++i) CHECK(sa.wire.x[i] == sb.wire.x[i]);
  // A copied state continues exactly like the original (model/state split).
  gw::EpisodeState s = gw::reset_episode(task, 0, 2, 9);
  for (int k = 0; k < 5; ++k) gw::step_episode(task, s, 0.5);
  gw::EpisodeState copy = s;
  const gw::StepOutcome o1 = gw::step_episode(task, s, -0.25);
  const gw::StepOutcome o2 = gw::step_episode(task, copy, -0.25);
  CHECK(same_bits(o1.obs, o2.obs));
}

TEST_CASE("stepping: wire advances, reward is Eq. 3 of the observation, action is recorded", "[task][episode]") {
  const gw::NavigationTask task = free_space_task(gwtest::y_graph());
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 3);
  const double inserted0 = s.wire.inserted_length_mm;
  gw::StepOutcome out;
  for (int k = 0; k < 25; ++k) {
    out = gw::step_episode(task, s, 0.6);
    REQUIRE_FALSE(out.truncated);
    CHECK(out.reward == gw::navigation_reward(out.obs[gw::obs_index::kOmega], out.obs[gw::obs_index::kLambda], 0.6,
                                              task.config.reward));
    CHECK(out.obs[gw::obs_index::kAction] == 0.6);  // single bifurcation: always in control
    CHECK(out.info.in_control);
  }
  const double advance = 25 * task.config.frame_skip * task.config.dt_s * task.config.push_mm_per_s;
  CHECK(s.wire.inserted_length_mm - inserted0 == Approx(advance).epsilon(1e-6));
  CHECK(out.obs[gw::obs_index::kLambda] < 1.0);       // closer to the target
  CHECK(out.obs[gw::obs_index::kSpeed] > 0.5);         // moving forward at about the push speed
  CHECK(out.obs[gw::obs_index::kSpeed] < 1.5);
  CHECK(out.info.progress_mm > 0.5 * advance);
  // Out-of-range actions are clipped, non-finite ones refused.
  out = gw::step_episode(task, s, 7.0);
  CHECK(out.obs[gw::obs_index::kAction] == 1.0);
  CHECK_THROWS_WITH(gw::step_episode(task, s, NAN), Catch::Contains("finite"));
}

TEST_CASE("push speed: the insertion follows the set speed and the speed observation stays normalised",
          "[task][episode]") {
  // A robot inserts at its own speed (navigate/evaluate/guidewire-server --push-speed): half the speed,
  // half the advance per step, and s = v.c / push still reads ~1 so an actor trained at 10 mm/s sees
  // the observation it knows.
  gw::TaskConfig slow;
  slow.push_mm_per_s = 5.0;
  const gw::NavigationTask task = free_space_task(gwtest::y_graph(), slow);
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 3);
  const double inserted0 = s.wire.inserted_length_mm;
  gw::StepOutcome out;
  for (int k = 0; k < 25; ++k) out = gw::step_episode(task, s, 0.0);
  CHECK(s.wire.inserted_length_mm - inserted0 == Approx(25 * 4 * 0.01 * 5.0).epsilon(1e-6));
  CHECK(out.obs[gw::obs_index::kSpeed] > 0.5);
  CHECK(out.obs[gw::obs_index::kSpeed] < 1.5);
  // A speed that is not > 0 is refused by name before any episode runs.
  for (const double bad : {0.0, -3.0, static_cast<double>(NAN)}) {
    gw::TaskConfig c;
    c.push_mm_per_s = bad;
    CHECK_THROWS_WITH(free_space_task(gwtest::y_graph(), c), Catch::Contains("push_mm_per_s"));
  }
}

TEST_CASE("trees: the action applies only within the control radius of a bifurcation", "[task][episode]") {
  gw::TaskConfig config;
  config.control_radius_mm = 10.0;
  const gw::NavigationTask task = free_space_task(gwtest::two_level_tree(), config);
  gw::EpisodeState s = gw::reset_episode(task, 0, 3, 1);  // a target behind two bifurcations
  REQUIRE(s.course->bifurcations.size() == 2);
  CHECK_FALSE(s.in_control);  // inlet is 40 mm from the first bifurcation
  bool was_in_control = false;
  for (int k = 0; k < 150 && !s.done; ++k) {
    const bool control = s.in_control;
    const double tip_to_bif = (s.tip - s.course->bifurcations[0].centre).norm();
    CHECK(control == (tip_to_bif <= config.control_radius_mm ||
                      (s.tip - s.course->bifurcations[1].centre).norm() <= config.control_radius_mm));
    const gw::StepOutcome out = gw::step_episode(task, s, 1.0);
    CHECK(out.obs[gw::obs_index::kAction] == (control ? 1.0 : 0.0));
    was_in_control = was_in_control || control;
  }
  CHECK(was_in_control);
}

TEST_CASE("trees: lambda runs to the intermediate target past the hand-over point", "[task][episode]") {
  const gw::NavigationTask task = free_space_task(gwtest::two_level_tree());
  gw::EpisodeState s = gw::reset_episode(task, 0, 3, 1);
  const gw::Course& c = *s.course;
  REQUIRE(c.bifurcations.size() == 2);
  REQUIRE(c.lambda_arc[0] > c.goal_arc[0]);
  CHECK(s.lambda0_mm == Approx(c.lambda_arc[0] - s.progress_mm));
  for (int k = 0; k < 100 && !s.done; ++k) {
    const gw::StepOutcome out = gw::step_episode(task, s, 0.0);
    CAPTURE(k, s.goal, s.progress_mm);
    CHECK(s.lambda_mm == Approx(std::max(0.0, c.lambda_arc[static_cast<std::size_t>(s.goal)] - s.progress_mm)));
    CHECK(out.obs[gw::obs_index::kLambda] == Approx(std::min(s.lambda_mm / s.lambda0_mm, 4.0)));
    if (s.goal == 0) CHECK(s.lambda_mm >= c.lambda_arc[0] - c.goal_arc[0] - 1e-9);  // never near 0 before it
  }
}

TEST_CASE("an episode ends: stepping after the end is refused", "[task][episode]") {
  gw::TaskConfig config;
  config.max_steps = 3;
  const gw::NavigationTask task = free_space_task(gwtest::y_graph(), config);
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 5);
  gw::step_episode(task, s, 0.0);
  gw::step_episode(task, s, 0.0);
  const gw::StepOutcome out = gw::step_episode(task, s, 0.0);
  CHECK(out.truncated);
  CHECK(out.info.step_limit);
  CHECK_FALSE(out.terminated);
  CHECK_THROWS_WITH(gw::step_episode(task, s, 0.0), Catch::Contains("episode is over"));
}

TEST_CASE("a time limit cuts a step off and ends the episode", "[task][episode]") {
  const gw::NavigationTask task = free_space_task(gwtest::y_graph());
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 5);
  gw::StepLimits limits;
  limits.wall_time_s = 1e-12;
  const gw::StepOutcome out = gw::step_episode(task, s, 0.0, limits);
  CHECK(out.truncated);
  CHECK(out.info.time_limit);
  CHECK_THAT(out.info.problem, Catch::Contains("time limit"));
  CHECK(s.done);
}

TEST_CASE("a wrong child bending back beside the access vessel is not 'entered' from the inlet", "[task][episode]") {
  const gw::CenterlineGraph g = gwtest::hook_graph();
  const gw::NavigationTask task = free_space_task(g);
  for (int target = 1; target <= 2; ++target) {
    gw::EpisodeState s = gw::reset_episode(task, 0, target, 4);
    for (int k = 0; k < 40; ++k) {  // 16 mm up the access vessel, the hook 12 mm away,
                                    // the continuation past the bifurcation >= 24 mm away
      const gw::StepOutcome out = gw::step_episode(task, s, 0.0);
      REQUIRE_FALSE(out.info.wrong_branch);
      REQUIRE_FALSE(out.terminated);
    }
  }
}

