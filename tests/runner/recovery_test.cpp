// Recovery (issue 37 item 1a, docs/recovery.md): after the strict end (first wrong branch, a stall) the
// procedure pulls the wire back before the bifurcation, turns it and advances again; the strict episode
// stays what it was, so one run gives both columns.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include "lib/report/trace_json.hpp"
#include "lib/runner/controller.hpp"
#include "lib/runner/episode_batch.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "lib/runner/run_episode.hpp"
#include "task/navigation_task.hpp"
#include "task/observation.hpp"
#include "engine/wire/wire_params.hpp"
#include "tests/runner/aim_controllers.hpp"

namespace {

const std::string kT1 = std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y";

gw::NavigationTask t1_task(int recovery_attempts) {
  static const gw::NavigationAnatomy nav =
      gw::load_navigation_anatomy(kT1 + ".stl", {1.0, std::nullopt, kT1 + ".truth.json", false});
  gw::TaskConfig c;
  c.recovery_attempts = recovery_attempts;
  return gw::make_navigation_task(c, gw::default_wire_params(), {nav.anatomy});
}

// Aims the tip at the wrong branch (as gwtest::AimAtWrongBranch) until it sees lambda jump up, which
// only a pull-back does (lambda_0 is measured afresh behind the bifurcation); from then on the scripted rule.
class WrongThenRight : public gw::Controller {
 public:
  const std::string& name() const override { return name_; }
  void begin_episode() override { last_lambda_ = 10, right_ = false; }
  gw::Action act(const gw::Observation& obs) override {
    const double lambda = obs[gw::obs_index::kLambda];
    right_ = right_ || lambda > last_lambda_ + 0.2;
    last_lambda_ = lambda;
    return {gwtest::aim_rotation(obs, !right_), 1.0};
  }

 private:
  std::string name_ = "wrong-then-right";
  double last_lambda_ = 10;
  bool right_ = false;
};

// The frames both traces have up to `last` are the same bits (time, tip, action, observation, force).
void require_same_frames(const gw::EpisodeTrace& a, const gw::EpisodeTrace& b, int last) {
  REQUIRE(static_cast<int>(a.time_s.size()) > last);
  REQUIRE(static_cast<int>(b.time_s.size()) > last);
  for (int f = 0; f <= last; ++f) {
    const auto i = static_cast<std::size_t>(f);
    REQUIRE(a.time_s[i] == b.time_s[i]);
    REQUIRE(a.tip[i] == b.tip[i]);
    REQUIRE(a.action[i] == b.action[i]);
    REQUIRE(std::memcmp(a.observation[i].data(), b.observation[i].data(), a.observation[i].size() * sizeof(double)) == 0);
    REQUIRE(a.wall_force_peak_node_mN[i] == b.wall_force_peak_node_mN[i]);
  }
}

}  // namespace

TEST_CASE("recovery: a wrong branch is pulled back from and the retry reaches the target", "[runner][recovery]") {
  const gw::NavigationTask strict = t1_task(0), recovering = t1_task(3);
  for (const gw::EpisodeRequest& r : std::vector<gw::EpisodeRequest>{{0, 1, 3}, {0, 2, 4}}) {
    WrongThenRight c0, c3;
    const gw::EpisodeTrace a = gw::run_episode(strict, r.anatomy, r.target_id, r.seed, c0);
    const gw::EpisodeTrace b = gw::run_episode(recovering, r.anatomy, r.target_id, r.seed, c3);
    REQUIRE(a.outcome == "wrong_branch");
    // The strict episode is the same in both runs, bit for bit, and ends at the same frame.
    REQUIRE(b.outcome == a.outcome);
    REQUIRE(b.detail == a.detail);
    CHECK(b.omega_at_loss == a.omega_at_loss);
    const int end = gw::strict_end(a);
    REQUIRE(b.strict_end_frame == end);
    require_same_frames(a, b, end);
    // Then it pulled back (retracting frames, the tip's progress down by the retract distance) and reached it.
    CHECK(b.recovery_attempts_allowed == 3);
    CHECK(b.recovery_attempts_used == 1);
    CHECK(b.recovery_outcome == "success");
    REQUIRE(b.retracting.size() == b.time_s.size());
    int retract_frames = 0;
    for (bool x : b.retracting) retract_frames += x;
    CHECK(retract_frames > 20);  // >= 8 mm at 0.4 mm per step
    CHECK_FALSE(b.retracting[static_cast<std::size_t>(end)]);
    CHECK(b.retracting[static_cast<std::size_t>(end) + 1]);
    // While pulling back no action is applied.
    for (std::size_t f = 0; f < b.time_s.size(); ++f)
      if (b.retracting[f]) CHECK(b.action[f] == 0.0);
    // The summary: strict figures as before, recovery beside them, and the trajectory file keeps both.
    const nlohmann::json summary = gw::summarize_episodes({b});
    const nlohmann::json& ep = summary["results"][0];
    CHECK(ep["outcome"] == "wrong_branch");
    CHECK(ep["steps"] == end);
    CHECK(ep["recovery"]["outcome"] == "success");
    CHECK(ep["recovery"]["attempts"] == 1);
    CHECK(ep["recovery"]["procedure_time_s"].get<double>() > ep["sim_time_s"].get<double>());
    CHECK(summary["recovery"]["successes"] == 1);
    CHECK(summary["successes"] == 0);
    const gw::EpisodeTrace back = gw::trace_from_json(gw::trace_to_json(b), "test");
    CHECK(back.strict_end_frame == end);
    CHECK(back.recovery_outcome == "success");
    CHECK(back.recovery_attempts_used == 1);
    CHECK(back.retracting == b.retracting);
  }
}

TEST_CASE("recovery: at most K attempts, then the loss stands, and 0 attempts is the strict episode", "[runner][recovery]") {
  const gw::NavigationTask strict = t1_task(0), recovering = t1_task(2);
  gwtest::AimAtWrongBranch c0, c2;
  const gw::EpisodeTrace a = gw::run_episode(strict, 0, 1, 3, c0);
  const gw::EpisodeTrace b = gw::run_episode(recovering, 0, 1, 3, c2);
  REQUIRE(a.outcome == "wrong_branch");
  CHECK(a.strict_end_frame == -1);  // no recovery: the trace is the strict episode's, as before
  CHECK(a.recovery_attempts_allowed == 0);
  CHECK(a.retracting.empty());
  CHECK_FALSE(gw::summarize_episodes({a})["results"][0].contains("recovery"));
  require_same_frames(a, b, gw::strict_end(a));
  CHECK(b.recovery_attempts_used == 2);
  CHECK(b.recovery_outcome != "success");
}

TEST_CASE("recovery: an episode that succeeds strictly is unchanged by it", "[runner][recovery]") {
  const gw::NavigationTask strict = t1_task(0), recovering = t1_task(3);
  auto c0 = gw::make_scripted_omega_controller(), c3 = gw::make_scripted_omega_controller();
  const gw::EpisodeTrace a = gw::run_episode(strict, 0, 2, 4, *c0);
  const gw::EpisodeTrace b = gw::run_episode(recovering, 0, 2, 4, *c3);
  REQUIRE(a.outcome == "success");
  REQUIRE(b.time_s.size() == a.time_s.size());
  require_same_frames(a, b, static_cast<int>(a.time_s.size()) - 1);
  CHECK(b.recovery_outcome == "success");
  CHECK(b.recovery_attempts_used == 0);
  // The force figures: positive on this walled anatomy, and the summary's are those of the frames.
  const nlohmann::json ep = gw::summarize_episodes({a})["results"][0];
  REQUIRE(ep.contains("force"));
  double peak = 0;
  for (double f : a.wall_force_peak_node_mN) peak = std::max(peak, f);
  CHECK(peak > 0);
  CHECK(ep["force"]["peak_node_N"].get<double>() == Approx(1e-3 * peak));
}

TEST_CASE("force limit: the trace keeps the time the push was withheld, its JSON and the figures the same sum",
          "[runner][force]") {
  gw::TaskConfig c = t1_task(0).config;
  c.force_limit_N = 0.001;  // far below what the wire presses with on this walled anatomy
  const gw::NavigationTask limited = gw::make_navigation_task(c, gw::default_wire_params(), t1_task(0).anatomies);
  auto scripted = gw::make_scripted_omega_controller();
  const gw::EpisodeTrace t = gw::run_episode(limited, 0, 2, 4, *scripted);
  REQUIRE(t.push_held_s.size() == t.time_s.size());
  double held = 0;
  for (double h : t.push_held_s) held += h;
  CHECK(held > 0);
  const nlohmann::json summary = gw::summarize_episodes({t});
  CHECK(summary["results"][0]["force"]["push_held_s"].get<double>() == Approx(held));
  CHECK(summary["force"]["mean_push_held_s"].get<double>() == Approx(held));
  CHECK(gw::trace_from_json(gw::trace_to_json(t), "test").push_held_s == t.push_held_s);
  // Without the limit nothing is recorded and the figures carry no such entry.
  const gw::EpisodeTrace free = gw::run_episode(t1_task(0), 0, 2, 4, *scripted);
  CHECK(free.push_held_s.empty());
  CHECK_FALSE(gw::summarize_episodes({free})["results"][0]["force"].contains("push_held_s"));
}
