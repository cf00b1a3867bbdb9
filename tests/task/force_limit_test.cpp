// The force limit (TaskConfig::force_limit_N, docs/recovery.md "Force limit"): for a physics step after one that
// pressed a wall node harder than the limit, the wire backs off at the push speed without turning instead of doing
// what it was told; the commanded forward push counts as pushed for the stall tests (act/1: no progress; act/2: wire pushed
// in without progress), so a wire held at the limit stalls, and with recovery the stall starts a pull-back.
// Off (0) it is the paper's task.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

#include "task/episode.hpp"

using Approx = Catch::Detail::Approx;

namespace {
const std::string kIndex = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";

// t4 (an S-curve, the wire meets the wall), one physics step per env step so that each env step's figures are
// those of the physics step the next push depends on.
gw::NavigationTask s_curve_task(double limit_N, bool push_pull, int recovery_attempts) {
  gw::TaskConfig c;
  c.frame_skip = 1;
  c.force_limit_N = limit_N;
  c.recovery_attempts = recovery_attempts;
  if (push_pull) {
    c.action = gw::ActionLayout::kRotationInsertion;
    c.observation.push_pull = true;
  }
  return gw::make_navigation_task(c, gw::default_wire_params(), gw::load_anatomies("train", kIndex));
}
constexpr int kAnatomy = 3, kTarget = 1, kSeed = 5;

// The largest single-node wall force (N) of the paper's episode there, turning at a constant 0.3.
double free_peak_N() {
  const gw::NavigationTask task = s_curve_task(0.0, false, 0);
  gw::EpisodeState s = gw::reset_episode(task, kAnatomy, kTarget, kSeed);
  double peak = 0;
  while (!s.done) peak = std::max(peak, gw::step_episode(task, s, 0.3).info.wall_force_peak_node_mN);
  return 1e-3 * peak;
}
}  // namespace

TEST_CASE("force limit: the wire backs off exactly after a physics step above the limit, and presses less",
          "[task][force]") {
  const double free_peak = free_peak_N();
  REQUIRE(free_peak > 0.1);
  const double limit = free_peak / 2;  // reached part-way along the curve
  const gw::NavigationTask free = s_curve_task(0.0, false, 0), limited = s_curve_task(limit, false, 0);
  gw::EpisodeState a = gw::reset_episode(free, kAnatomy, kTarget, kSeed);
  gw::EpisodeState b = gw::reset_episode(limited, kAnatomy, kTarget, kSeed);
  const double step_mm = limited.config.dt_s * limited.config.push_mm_per_s;
  double last_peak_mN = 0.0, last_inserted_mm = b.wire.inserted_length_mm, peak_mN = 0.0;
  bool parted = false;  // the two episodes are the same one until the limit first acts
  int held = 0;
  gw::StepOutcome out;
  while (!b.done) {
    const bool expect_held = last_peak_mN > 1e3 * limit;
    out = gw::step_episode(limited, b, 0.3);
    REQUIRE(out.info.push_held_steps == (expect_held ? 1 : 0));
    if (expect_held) {  // backed off by one physics step's push, not pushed on
      CHECK(b.wire.inserted_length_mm == Approx(last_inserted_mm - step_mm));
      ++held;
    } else {
      CHECK(b.wire.inserted_length_mm == Approx(last_inserted_mm + step_mm));
    }
    if (!parted && !a.done) {
      const gw::StepOutcome oa = gw::step_episode(free, a, 0.3);
      CHECK(oa.info.push_held_steps == 0);
      if (expect_held)
        parted = true;
      else
        REQUIRE(a.tip == b.tip);
    }
    last_peak_mN = out.info.wall_force_peak_node_mN;
    last_inserted_mm = b.wire.inserted_length_mm;
    peak_mN = std::max(peak_mN, last_peak_mN);
  }
  CHECK(parted);
  CHECK(held > 0);
  // Each backed-off step counts its commanded push and the step it went back: the stall test sees the push.
  CHECK(b.force.withheld_mm == Approx(2 * held * step_mm));
  CHECK(1e-3 * peak_mN < free_peak);
  // Held at the wall the tip makes no progress: the paper's stall ends the episode.
  CHECK(out.info.stuck);
  CHECK(out.truncated);
}

TEST_CASE("force limit, push/pull: the withheld push counts as wire pushed in without progress", "[task][force]") {
  const gw::NavigationTask task = s_curve_task(free_peak_N() / 2, true, 0);
  gw::EpisodeState s = gw::reset_episode(task, kAnatomy, kTarget, kSeed);
  gw::StepOutcome out;
  while (!s.done) out = gw::step_episode(task, s, gw::Action{0.3, 1.0});
  REQUIRE(s.done);
  REQUIRE(out.info.stuck);
  const double stall_mm = task.config.stuck_steps * task.config.frame_skip * task.config.dt_s * task.config.push_mm_per_s;
  CHECK(s.force.withheld_mm > 0);
  // The wire itself went in less than a stall's length past its best: the withheld pushes made up the rest.
  CHECK(s.wire.inserted_length_mm - s.stall.inserted_at_best_mm < stall_mm);
  CHECK(s.wire.inserted_length_mm + s.force.withheld_mm - s.stall.inserted_at_best_mm >= stall_mm);
}

TEST_CASE("force limit with recovery: the stall at the limit starts a pull-back, which the limit never holds",
          "[task][force]") {
  const gw::NavigationTask task = s_curve_task(free_peak_N() / 2, false, 1);
  gw::EpisodeState s = gw::reset_episode(task, kAnatomy, kTarget, kSeed);
  bool pulled = false;
  for (int k = 0; k < 20000 && !s.done; ++k) {
    const double inserted = s.wire.inserted_length_mm;
    const gw::StepOutcome out = gw::step_episode(task, s, 0.3);
    if (out.info.retracting) {
      pulled = true;
      CHECK(out.info.push_held_steps == 0);
      CHECK(s.wire.inserted_length_mm < inserted);
    }
    if (pulled && !s.procedure.retracting) break;
  }
  CHECK(pulled);
  CHECK(s.procedure.attempts_used == 1);
}

TEST_CASE("force limit: off by default, and checked", "[task][force]") {
  gw::TaskConfig c;
  CHECK(c.force_limit_N == 0.0);
  CHECK_NOTHROW(gw::check_task_config(c));
  c.force_limit_N = -0.5;
  CHECK_THROWS_WITH(gw::check_task_config(c), Catch::Contains("force_limit_N"));
  c.force_limit_N = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(gw::check_task_config(c), Catch::Contains("force_limit_N"));
}
