// Safety figures (issue 37 item 4): the wall force of a step from WireState::contact_force, and the
// figures StepInfo reports for an env step on a real wall.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <utility>

#include "task/episode.hpp"
#include "task/episode_stages.hpp"
#include "task/wall_force.hpp"

using Approx = Catch::Detail::Approx;

namespace {
const std::string kIndex = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";
}  // namespace

TEST_CASE("wall force: the largest node, the sum of magnitudes and the distal 1 mm", "[task][force]") {
  gw::NavigationTask task = gw::make_navigation_task({}, gw::default_wire_params(), gw::load_anatomies("train", kIndex));
  const gw::WireModel& model = gw::wire_of(task, 0);
  gw::WireState s = gw::make_initial_state(model, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, 50.0);
  CHECK(gw::wall_force(model, s).total_mN == 0.0);
  const int n = model.nodes;
  s.contact_force[static_cast<size_t>(n / 2)] = Eigen::Vector3d(3, 4, 0);     // 5 mN mid-wire
  s.contact_force[static_cast<size_t>(n - 1)] = Eigen::Vector3d(0, 0, 2);     // distal node
  s.contact_force[static_cast<size_t>(n - 2)] = Eigen::Vector3d(0, 0, 1);     // 0.5 mm from the tip
  const gw::WallForce f = gw::wall_force(model, s);
  CHECK(f.peak_node_mN == Approx(5.0));
  CHECK(f.total_mN == Approx(8.0));
  CHECK(f.tip_mN == Approx(3.0));  // both distal nodes lie within kTipForceLengthMm, summed as vectors
  REQUIRE(model.arc_from_tip[static_cast<size_t>(n - 2)] <= gw::kTipForceLengthMm);
}

TEST_CASE("wall force: StepInfo reports the step's contact force, positive once the wire touches the wall",
          "[task][force]") {
  gw::TaskConfig config;
  config.frame_skip = 1;  // one physics step per env step: the figures are those of the state after it
  const gw::NavigationTask task =
      gw::make_navigation_task(config, gw::default_wire_params(), gw::load_anatomies("train", kIndex));
  gw::EpisodeState s = gw::reset_episode(task, 3, 1, 5);  // t4: an S-curve, the wire meets the wall
  bool touched = false;
  for (int k = 0; k < 1500 && !s.done; ++k) {
    const gw::StepOutcome out = gw::step_episode(task, s, 0.0);
    double total = 0, peak = 0;
    for (const Eigen::Vector3d& f : s.wire.contact_force) {
      total += f.norm();
      peak = std::max(peak, f.norm());
    }
    CHECK(out.info.wall_force_peak_total_mN == Approx(total).margin(1e-12));
    CHECK(out.info.wall_force_mean_total_mN == Approx(total).margin(1e-12));
    CHECK(out.info.wall_force_peak_node_mN == Approx(peak).margin(1e-12));
    CHECK(out.info.tip_force_mN <= out.info.wall_force_peak_total_mN + 1e-12);
    if (out.info.contacts > 0 && total > 0) {
      touched = true;
      CHECK(out.info.wall_force_peak_node_mN > 0);
      break;
    }
  }
  CHECK(touched);
}

TEST_CASE("obs/8: the tip-force entry is the env step's tip force over 1.5 N (clipped) and 0 at reset", "[task][force]") {
  gw::TaskConfig config;
  config.action = gw::ActionLayout::kRotationInsertion;
  config.observation = gw::ObservationLayout::parse("guidewire-nav/obs/8");
  const gw::NavigationTask task =
      gw::make_navigation_task(config, gw::default_wire_params(), gw::load_anatomies("train", kIndex));
  gw::EpisodeState s = gw::reset_episode(task, 3, 1, 5);  // t4: an S-curve, the wire meets the wall
  CHECK(s.obs[gw::obs_index::kTipForce] == 0.0);
  bool pressed = false;
  for (int k = 0; k < 400 && !s.done; ++k) {
    const gw::StepOutcome out = gw::step_episode(task, s, gw::Action{0.0, 1.0});
    const double expected = std::min(out.info.tip_force_mN / 1500.0, gw::kTipForceCap);
    REQUIRE(out.obs[gw::obs_index::kTipForce] == Approx(expected).margin(1e-12));
    pressed = pressed || expected > 0;
  }
  CHECK(pressed);
}

TEST_CASE("recovery settings: off by default, checked", "[task][recovery]") {
  gw::TaskConfig c;
  CHECK(c.recovery_attempts == 0);
  CHECK_NOTHROW(gw::check_task_config(c));
  c.recovery_attempts = -1;
  CHECK_THROWS_WITH(gw::check_task_config(c), Catch::Contains("recovery_attempts"));
  c.recovery_attempts = 3;
  c.recovery_retract_mm = 0;
  CHECK_THROWS_WITH(gw::check_task_config(c), Catch::Contains("recovery_retract_mm"));
  c.recovery_retract_mm = 20;
  c.recovery_pull_mm_per_s = -1;
  CHECK_THROWS_WITH(gw::check_task_config(c), Catch::Contains("recovery_pull_mm_per_s"));
}

TEST_CASE("force penalty: off by default, and on, the reward loses weight x the step's peak node force over 1.5 N",
          "[task][force]") {
  gw::TaskConfig plain, penalised;
  CHECK(plain.reward_force_per_N == 0.0);
  penalised.reward_force_per_N = 2.0;
  const auto anatomies = gw::load_anatomies("train", kIndex);
  const gw::NavigationTask a = gw::make_navigation_task(plain, gw::default_wire_params(), anatomies);
  const gw::NavigationTask b = gw::make_navigation_task(penalised, gw::default_wire_params(), anatomies);
  gw::EpisodeState sa = gw::reset_episode(a, 3, 1, 5), sb = gw::reset_episode(b, 3, 1, 5);
  bool pressed = false;
  for (int k = 0; k < 400 && !sa.done && !pressed; ++k) {
    const gw::StepOutcome oa = gw::step_episode(a, sa, 0.3), ob = gw::step_episode(b, sb, 0.3);
    REQUIRE(oa.info.wall_force_peak_node_mN == ob.info.wall_force_peak_node_mN);  // same episode
    const double over_safe_N = std::max(0.0, 1e-3 * oa.info.wall_force_peak_node_mN - 1.5);
    CHECK(ob.reward == Approx(oa.reward - 2.0 * over_safe_N).margin(1e-12));
    pressed = oa.info.wall_force_peak_node_mN > 0;
  }
  CHECK(pressed);  // the wire touched the wall (below 1.5 N the two rewards are the same)
  gw::PhysicsSummary physics;
  for (const auto& [node_mN, cost] : {std::pair{0.0, 0.0}, {1000.0, 0.0}, {1500.0, 0.0}, {3000.0, 3.0}, {51500.0, 100.0}}) {
    physics.peak.peak_node_mN = node_mN;
    physics.peak.total_mN = 10 * node_mN;  // the total is not what is charged
    CHECK(gw::force_cost(penalised, physics) == Approx(cost).margin(1e-12));
    CHECK(gw::force_cost(plain, physics) == 0.0);
  }
  gw::TaskConfig bad;
  bad.reward_force_per_N = -1;
  CHECK_THROWS_WITH(gw::check_task_config(bad), Catch::Contains("reward_force_per_N"));
}
