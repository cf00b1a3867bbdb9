// Tip reshape (issue 37, docs/recovery.md): a procedure that does not reach the target is withdrawn, the
// wire's tip reshaped, and navigated again from the inlet. The first pass stays what it was; the second is
// the reshaped wire's own episode; the "reshape" figures add both passes and the withdrawal between them.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "lib/report/trace_json.hpp"
#include "lib/runner/controller.hpp"
#include "lib/runner/episode_batch.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "lib/runner/navigation_outputs.hpp"
#include "lib/runner/run_episode.hpp"
#include "task/navigation_task.hpp"
#include "engine/wire/wire_params.hpp"

namespace {

// A validation tree (in no row of the results table) whose target 1 leaves at 30 degrees on the inner side
// of the access: the wire's own tip (0.2 /mm) goes straight on past it whatever its aim, a tip reshaped to
// 0.3 /mm gets in.
const std::string kPl = std::string(GW_SOURCE_DIR) + "/anatomies/validation/pl_validation/pl_validation";

const gw::NavigationAnatomy& pl_nav() {
  static const gw::NavigationAnatomy nav =
      gw::load_navigation_anatomy(kPl + ".stl", {1.0, std::nullopt, kPl + ".truth.json", false});
  return nav;
}

gw::NavigationTask pl_task() {
  return gw::make_navigation_task(gw::TaskConfig{}, gw::default_wire_params(), {pl_nav().anatomy});
}

void require_same_frames(const gw::EpisodeTrace& a, const gw::EpisodeTrace& b) {
  REQUIRE(a.time_s.size() == b.time_s.size());
  for (std::size_t f = 0; f < a.time_s.size(); ++f) {
    REQUIRE(a.time_s[f] == b.time_s[f]);
    REQUIRE(a.tip[f] == b.tip[f]);
    REQUIRE(a.action[f] == b.action[f]);
    REQUIRE(std::memcmp(a.observation[f].data(), b.observation[f].data(), a.observation[f].size() * sizeof(double)) == 0);
  }
}

}  // namespace

TEST_CASE("reshape: a lost procedure is withdrawn and the reshaped tip reaches the target", "[runner][reshape]") {
  const gw::NavigationTask task = pl_task();
  const gw::NavigationTask reshaped = gw::make_reshaped_task(task, 0.3);
  CHECK(reshaped.wires[0].params.tip_curvature_per_mm == 0.3);
  CHECK(reshaped.wires[0].params.tip_length_mm == task.wires[0].params.tip_length_mm);
  gw::TraceOptions plain, with;
  with.reshaped = &reshaped;
  auto c0 = gw::make_scripted_omega_controller(), c1 = gw::make_scripted_omega_controller();
  const gw::EpisodeTrace a = gw::run_episode(task, 0, 1, 1000, *c0, plain);
  const gw::EpisodeTrace b = gw::run_episode(task, 0, 1, 1000, *c1, with);
  REQUIRE(a.outcome == "wrong_branch");
  CHECK(a.reshaped.empty());
  CHECK(a.reshape_tip_per_mm == 0.0);
  // The first pass is the episode without reshape, bit for bit; the second starts again from the inlet.
  REQUIRE(b.outcome == a.outcome);
  require_same_frames(a, b);
  REQUIRE(b.reshaped.size() == 1);
  const gw::EpisodeTrace& second = b.reshaped.front();
  CHECK(second.outcome == "success");
  CHECK(second.time_s.front() == 0.0);
  CHECK((second.tip.front() - a.tip.front()).norm() < 1.0);  // the same 2 mm insertion, a tip bent more
  CHECK(b.reshape_tip_per_mm == 0.3);
  CHECK(b.reshape_withdrawal_s > 0.0);

  // The summary: the strict figures are the first pass's; "reshape" adds both passes and the withdrawal.
  const nlohmann::json summary = gw::summarize_episodes({b});
  const nlohmann::json& ep = summary["results"][0];
  CHECK(ep["outcome"] == "wrong_branch");
  const nlohmann::json& r = ep["reshape"];
  CHECK(r["outcome"] == "success");
  CHECK(r["reshaped"] == true);
  CHECK(r["tip_curvature_per_mm"] == 0.3);
  CHECK(r["withdrawal_s"].get<double>() == b.reshape_withdrawal_s);
  CHECK(r["procedure_time_s"].get<double>() == a.time_s.back() + b.reshape_withdrawal_s + second.time_s.back());
  CHECK(r["steps"].get<int>() == static_cast<int>(a.time_s.size() + second.time_s.size()) - 2);
  double peak = 0;
  for (const gw::EpisodeTrace* t : {&a, &second})
    for (double f : t->wall_force_peak_node_mN) peak = std::max(peak, f);
  CHECK(r["force"]["peak_node_N"].get<double>() == Approx(1e-3 * peak));
  CHECK(summary["successes"] == 0);
  CHECK(summary["reshape"]["successes"] == 1);
  CHECK(summary["reshape"]["reshaped"] == 1);
  CHECK(summary["reshape"]["tip_curvature_per_mm"] == 0.3);
  // Joined again from the results alone (evaluate --from-json), the same figures.
  CHECK(gw::summarize_results(summary["results"])["reshape"] == summary["reshape"]);

  // navigate --out: the second pass's trajectory beside the first's.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gw_reshape_outputs";
  std::filesystem::remove_all(dir);
  gw::write_navigation_outputs(dir.string(), pl_nav(), {b}, {"test"});
  CHECK(gw::read_trace_json((dir / "episode0_target1.json").string()).time_s.size() == a.time_s.size());
  const gw::EpisodeTrace written = gw::read_trace_json((dir / "episode0_target1_reshaped.json").string());
  CHECK(written.outcome == "success");
  CHECK(written.time_s.size() == second.time_s.size());
  CHECK(std::filesystem::exists(dir / "episode0_target1_reshaped.vtp"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("reshape: a procedure that reaches the target is not reshaped", "[runner][reshape]") {
  const gw::NavigationTask task = pl_task();
  const gw::NavigationTask reshaped = gw::make_reshaped_task(task, 0.3);
  gw::TraceOptions with;
  with.reshaped = &reshaped;
  auto c = gw::make_scripted_omega_controller();
  const gw::EpisodeTrace t = gw::run_episode(task, 0, 3, 1000, *c, with);
  REQUIRE(t.outcome == "success");
  CHECK(t.reshaped.empty());
  CHECK(t.reshape_withdrawal_s == 0.0);
  const nlohmann::json r = gw::summarize_episodes({t})["results"][0]["reshape"];
  CHECK(r["outcome"] == "success");
  CHECK(r["reshaped"] == false);
  CHECK(r["procedure_time_s"].get<double>() == t.time_s.back());
  CHECK_FALSE(r.contains("withdrawal_s"));
}

TEST_CASE("reshape: the curvature must be a number above 0", "[runner][reshape]") {
  const gw::NavigationTask task = pl_task();
  for (double bad : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN()})
    CHECK_THROWS_WITH(gw::make_reshaped_task(task, bad), Catch::Contains("tip reshape: the curvature must be"));
}

TEST_CASE("reshape: the wire's own curvature over a longer tip reaches the target the first pass missed",
          "[runner][reshape]") {
  // pl_validation target 5 (in no row of the table), at the end of the main vessel's 0.8 mm narrowing: the
  // wire's own tip goes the wrong way, the same curvature bent over 9 mm gets in.
  const gw::NavigationTask task = pl_task();
  const gw::NavigationTask longer = gw::make_reshaped_task(task, 0.2, 9.0);
  CHECK(longer.wires[0].params.tip_curvature_per_mm == 0.2);
  CHECK(longer.wires[0].params.tip_length_mm == 9.0);
  gw::TraceOptions with;
  with.reshaped = &longer;
  auto c = gw::make_scripted_omega_controller();
  // Seed 1001: seed 1000's first pass has reached the target too since a tip wedged in a crease is held by
  // both walls (engine/contact/detect_contacts.hpp, kCreaseDepthMm); 1001-1007 still go the wrong way.
  const gw::EpisodeTrace t = gw::run_episode(task, 0, 5, 1001, *c, with);
  REQUIRE(t.outcome != "success");
  REQUIRE(t.reshaped.size() == 1);
  CHECK(t.reshaped.front().outcome == "success");
  CHECK(t.reshape_tip_length_mm == 9.0);
  const nlohmann::json summary = gw::summarize_episodes({t});
  CHECK(summary["results"][0]["reshape"]["tip_length_mm"] == 9.0);
  CHECK(summary["reshape"]["tip_length_mm"] == 9.0);
  CHECK(summary["reshape"]["successes"] == 1);
}

TEST_CASE("reshape: the tip length must be 0 or a number above 0 shorter than the wire", "[runner][reshape]") {
  const gw::NavigationTask task = pl_task();
  CHECK(gw::make_reshaped_task(task, 0.3, 0.0).wires[0].params.tip_length_mm == task.wires[0].params.tip_length_mm);
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), task.wires[0].params.length_mm})
    CHECK_THROWS_WITH(gw::make_reshaped_task(task, 0.3, bad), Catch::Contains("tip reshape: the tip length must be"));
}
