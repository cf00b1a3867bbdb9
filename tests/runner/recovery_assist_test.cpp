// Assisted recovery for a push/pull actor (TaskConfig::recovery_assist, docs/recovery.md "Assisted recovery"):
// with recovery the wrapper's pull-back steps in where an act/2 actor does not recover by itself: after a stall
// (one of the K attempts, where without it the stall ends the procedure) and when the tip has stayed stuck_steps
// env steps in a wrong child (no new attempt: the entry used one) and, once the strict episode is over, when the
// actor stands still (one attempt). The actor gets the wire back afterwards.
#include <catch2/catch.hpp>
#include <algorithm>

#include "lib/runner/navigation_anatomy.hpp"
#include "task/episode.hpp"
#include "task/navigation_task.hpp"
#include "task/observation.hpp"
#include "engine/wire/wire_params.hpp"
#include "tests/runner/aim_controllers.hpp"

using Approx = Catch::Detail::Approx;

namespace {

const std::string kT1 = std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y";
const std::string kIndex = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";

gw::TaskConfig push_pull_config(int recovery_attempts, bool assist) {
  gw::TaskConfig c;
  c.action = gw::ActionLayout::kRotationInsertion;
  c.observation.push_pull = true;
  c.recovery_attempts = recovery_attempts;
  c.recovery_assist = assist;
  return c;
}

gw::NavigationTask t1_task(bool assist, int recovery_attempts = 1) {
  static const gw::NavigationAnatomy nav =
      gw::load_navigation_anatomy(kT1 + ".stl", {1.0, std::nullopt, kT1 + ".truth.json", false});
  gw::TaskConfig c = push_pull_config(recovery_attempts, assist);
  c.observation.omega_side = true;
  return gw::make_navigation_task(c, gw::default_wire_params(), {nav.anatomy});
}

// t4 (an S-curve where the pushed wire meets the wall), one physics step per env step, with a force limit at half
// the largest node force the constant push at rotation 0.3 reaches there: the wire is held at the limit and stalls.
gw::NavigationTask s_curve_task(bool assist) {
  const auto anatomies = gw::load_anatomies("train", kIndex);
  gw::TaskConfig free;
  free.frame_skip = 1;
  const gw::NavigationTask paper = gw::make_navigation_task(free, gw::default_wire_params(), anatomies);
  gw::EpisodeState s = gw::reset_episode(paper, 3, 1, 5);
  double peak_mN = 0;
  while (!s.done) peak_mN = std::max(peak_mN, gw::step_episode(paper, s, 0.3).info.wall_force_peak_node_mN);
  gw::TaskConfig c = push_pull_config(1, assist);
  c.frame_skip = 1;
  c.force_limit_N = 1e-3 * peak_mN / 2;
  return gw::make_navigation_task(c, gw::default_wire_params(), anatomies);
}

}  // namespace

TEST_CASE("recovery assist: a tip left in a wrong child is pulled out after stuck_steps, no new attempt",
          "[runner][push_pull][recovery]") {
  for (const bool assist : {false, true}) {
    CAPTURE(assist);
    const gw::NavigationTask task = t1_task(assist);
    gw::EpisodeState s = gw::reset_episode(task, 0, 1, 5);
    gw::StepOutcome out;
    do out = gw::step_episode(task, s, gw::Action{gwtest::aim_rotation(s.obs, true), 1.0});
    while (!out.info.strict_end && !s.done);
    REQUIRE(out.info.wrong_branch);
    REQUIRE(out.info.recovery_attempts == 1);
    // The actor holds the wire still in the wrong child: no stall (nothing pushed), so only the assist acts.
    int held = 1;  // the entry step counts
    while (!s.procedure.retracting && held < 3 * task.config.stuck_steps) {
      out = gw::step_episode(task, s, gw::Action{0.0, 0.0});
      REQUIRE_FALSE(s.done);
      ++held;
    }
    if (!assist) {
      CHECK_FALSE(s.procedure.retracting);
      continue;
    }
    REQUIRE(s.procedure.retracting);
    CHECK(held == task.config.stuck_steps);
    CHECK_FALSE(out.info.in_control);
    CHECK(s.procedure.attempts_used == 1);  // the entry's attempt: the pull-back uses none
    // The wrapper pulls it out: the flag clears while the wire comes back, whatever the actor asks.
    int pulled = 0;
    while (s.procedure.retracting && pulled < 500) {
      const double inserted = s.wire.inserted_length_mm;
      out = gw::step_episode(task, s, gw::Action{1.0, 1.0});
      CHECK(out.info.retracting);
      CHECK(s.wire.inserted_length_mm < inserted);
      ++pulled;
    }
    REQUIRE_FALSE(s.procedure.retracting);
    REQUIRE_FALSE(s.done);
    CHECK(s.obs[gw::obs_index::kWrongBranch] == 0.0);
    CHECK(s.progress_mm <= s.procedure.retract_to_mm + 0.5);
    CHECK(out.info.recovery_attempts == 1);
  }
}

TEST_CASE("recovery assist: a stall starts a pull-back with one attempt instead of ending the procedure",
          "[runner][push_pull][recovery][force]") {
  const gw::NavigationTask off = s_curve_task(false), on = s_curve_task(true);
  gw::EpisodeState a = gw::reset_episode(off, 3, 1, 5), b = gw::reset_episode(on, 3, 1, 5);
  gw::StepOutcome oa, ob;
  // The same episode up to the stall.
  do {
    oa = gw::step_episode(off, a, gw::Action{0.3, 1.0});
    ob = gw::step_episode(on, b, gw::Action{0.3, 1.0});
    REQUIRE(a.tip == b.tip);
  } while (!a.done);
  REQUIRE(oa.info.stuck);
  REQUIRE(oa.info.strict_end);
  CHECK(oa.truncated);
  CHECK(a.procedure.attempts_used == 0);
  // Assisted: the strict end is the same stall, the procedure goes on with a pull-back.
  CHECK(ob.info.strict_end);
  CHECK(ob.info.stuck);
  CHECK_FALSE(ob.truncated);
  CHECK_FALSE(ob.terminated);
  CHECK_FALSE(b.done);
  CHECK(b.procedure.retracting);
  CHECK(b.procedure.attempts_used == 1);
  while (b.procedure.retracting && !b.done) ob = gw::step_episode(on, b, gw::Action{0.3, 1.0});
  REQUIRE_FALSE(b.done);
  // The stall test starts again from the pulled-back wire: pushing on, no stall before stuck_steps full pushes.
  const int from = b.steps;
  while (!b.done) ob = gw::step_episode(on, b, gw::Action{0.3, 1.0});
  CHECK(b.steps - from >= on.config.stuck_steps);
  // With its one attempt used, a second stall ends the procedure (or the tip got past and the episode ended there).
  if (ob.info.stuck) {
    CHECK(ob.truncated);
    CHECK(b.procedure.attempts_used == 1);
  }
}

TEST_CASE("recovery assist: a standstill after the strict end starts a pull-back with one attempt",
          "[runner][push_pull][recovery]") {
  const gw::NavigationTask off = t1_task(false, 2), on = t1_task(true, 2);
  gw::EpisodeState a = gw::reset_episode(off, 0, 1, 5), b = gw::reset_episode(on, 0, 1, 5);
  // 40 env steps of pushing (16 mm, short of the fork), then the actor stands still: nothing is pushed, so no
  // stall, and the strict episode runs to its step limit, the same with and without the assist.
  auto act = [](const gw::EpisodeState& s) { return gw::Action{0.0, s.steps < 40 ? 1.0 : 0.0}; };
  gw::StepOutcome oa, ob;
  do {
    oa = gw::step_episode(off, a, act(a));
    ob = gw::step_episode(on, b, act(b));
    REQUIRE(a.tip == b.tip);
  } while (!oa.info.strict_end);
  REQUIRE(ob.info.strict_end);
  REQUIRE(oa.info.step_limit);
  CHECK(ob.info.step_limit);  // the strict verdict, for the strict columns
  CHECK_FALSE(ob.info.stuck);
  // Without the assist the actor stays where it is until the procedure's time runs out.
  CHECK_FALSE(a.procedure.retracting);
  while (!a.done) {
    oa = gw::step_episode(off, a, act(a));
    CHECK_FALSE(a.procedure.retracting);
  }
  CHECK(oa.info.step_limit);
  CHECK(a.procedure.attempts_used == 0);
  // Assisted: the standstill (since step 40, longer than stuck_steps) starts a pull-back at the strict end.
  CHECK_FALSE(ob.truncated);
  REQUIRE(b.procedure.retracting);
  CHECK(b.procedure.attempts_used == 1);
  const double before = b.wire.inserted_length_mm;
  while (b.procedure.retracting && !b.done) ob = gw::step_episode(on, b, act(b));
  REQUIRE_FALSE(b.done);
  CHECK(b.wire.inserted_length_mm < before - 5.0);
  // The clock starts again at the end of the pull-back: standing still again, the second (last) attempt starts
  // exactly stuck_steps env steps later, and with none left the actor is then left standing until time runs out.
  const int from = b.steps;
  while (!b.procedure.retracting && !b.done) ob = gw::step_episode(on, b, act(b));
  REQUIRE(b.procedure.retracting);
  CHECK(b.steps - from == on.config.stuck_steps);
  CHECK(b.procedure.attempts_used == 2);
  while (b.procedure.retracting && !b.done) ob = gw::step_episode(on, b, act(b));
  while (!b.done) {
    ob = gw::step_episode(on, b, act(b));
    CHECK_FALSE(b.procedure.retracting);
  }
  CHECK(ob.info.step_limit);
  CHECK(b.procedure.attempts_used == 2);
}

TEST_CASE("recovery assist: needs recovery attempts", "[runner][push_pull][recovery]") {
  gw::TaskConfig c = push_pull_config(0, true);
  CHECK_THROWS_WITH(gw::check_task_config(c), Catch::Contains("recovery_assist"));
  c.recovery_attempts = 2;
  CHECK_NOTHROW(gw::check_task_config(c));
  CHECK_FALSE(gw::TaskConfig{}.recovery_assist);
}
