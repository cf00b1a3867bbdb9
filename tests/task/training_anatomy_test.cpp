// Episodes on the real training anatomies (mesh wall, contact): every target plans, the start is
// inside the vessel, and the same seed and actions reproduce the trajectory bit for bit.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <thread>

#include "task/episode.hpp"

namespace {
const std::string kIndex = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";

const gw::NavigationTask& training_task() {
  static const gw::NavigationTask task =
      gw::make_navigation_task({}, gw::default_wire_params(), gw::load_anatomies("train", kIndex));
  return task;
}
}  // namespace

TEST_CASE("training anatomies: courses and episode lengths fit the task design", "[task][training]") {
  const gw::NavigationTask& task = training_task();
  REQUIRE(task.anatomies.size() == 4);
  const double advance = task.config.push_mm_per_s * task.config.dt_s * task.config.frame_skip;
  for (size_t a = 0; a < task.anatomies.size(); ++a) {
    REQUIRE(task.courses[a].size() == 2);
    for (const gw::Course& c : task.courses[a]) {
      CHECK(c.bifurcations.size() == 1);
      CHECK(c.policy_always);
      // "A few hundred env steps" for a wire that advances at the push speed.
      CHECK(c.line.length / advance > 150);
      CHECK(c.line.length / advance < 500);
    }
    const gw::EpisodeState s = gw::reset_episode(task, static_cast<int>(a), 1, 3);
    CHECK(gw::wall_distance(*task.anatomies[a].scene, s.tip).signed_distance > 0);  // tip inside the lumen
  }
}

TEST_CASE("training anatomies: same seed and actions give the same trajectory bit for bit", "[task][training]") {
  const gw::NavigationTask& task = training_task();
  auto run = [&](int anatomy) {
    gw::EpisodeState s = gw::reset_episode(task, anatomy, 2, 17);
    std::vector<double> trace;
    for (int k = 0; k < 25 && !s.done; ++k) {
      const gw::StepOutcome o = gw::step_episode(task, s, std::cos(0.4 * k));
      trace.insert(trace.end(), o.obs.begin(), o.obs.end());
      trace.push_back(o.reward);
    }
    for (const auto& x : s.wire.x) trace.insert(trace.end(), {x.x(), x.y(), x.z()});
    return trace;
  };
  for (int anatomy : {0, 3}) {
    const std::vector<double> a = run(anatomy), b = run(anatomy);
    REQUIRE(a.size() == b.size());
    CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
  }
}

TEST_CASE("training anatomies: episodes in parallel threads share the task safely", "[task][training]") {
  // The server runs one episode per connection thread over one constant task (scene, courses).
  const gw::NavigationTask& task = training_task();
  auto run = [&](int anatomy, std::vector<double>& trace) {
    gw::EpisodeState s = gw::reset_episode(task, anatomy, 1, 99);
    for (int k = 0; k < 15 && !s.done; ++k) trace.push_back(gw::step_episode(task, s, std::sin(0.5 * k)).reward);
  };
  std::vector<double> seq0, seq1, par0, par1;
  run(1, seq0);
  run(2, seq1);
  std::thread t0([&] { run(1, par0); });
  std::thread t1([&] { run(2, par1); });
  t0.join();
  t1.join();
  CHECK(par0 == seq0);
  CHECK(par1 == seq1);
}
