// Joining results tables run on different seeds: counts add up, episodes pair across runs, and runs
// that do not fit together are refused by name.
#include <catch2/catch.hpp>
#include <utility>
#include <vector>

#include "lib/runner/episode_batch.hpp"
#include "lib/runner/evaluation_merge.hpp"
#include "lib/runner/evaluation_table.hpp"

namespace {

nlohmann::json episode(int target, int seed, bool success) {
  return {{"anatomy", "coronary"}, {"target", target}, {"seed", seed},
          {"outcome", success ? "success" : "wrong_branch"}, {"detail", ""}};
}

// A column over `outcomes` (one episode per seed from `first_seed`, all on target 1).
nlohmann::json column(int first_seed, const std::vector<bool>& outcomes) {
  nlohmann::json results = nlohmann::json::array();
  int ok = 0;
  for (std::size_t k = 0; k < outcomes.size(); ++k) {
    results.push_back(episode(1, first_seed + static_cast<int>(k), outcomes[k]));
    ok += outcomes[k];
  }
  const int n = static_cast<int>(outcomes.size());
  return {{"episodes", n}, {"successes", ok}, {"success_rate", static_cast<double>(ok) / n},
          {"outcomes", {{"success", ok}, {"wrong_branch", n - ok}}}, {"results", results}};
}

nlohmann::json run(int first_seed, const std::vector<bool>& sac, const std::vector<bool>& scripted, int reached) {
  nlohmann::json row = {{"name", "coronary-like"}, {"episodes", sac.size()}, {"paper", 0.94},
                        {"notes", nlohmann::json::array()}, {"wall_time_s", 10.0},
                        {"results", {{"sac-policy", column(first_seed, sac)},
                                     {"scripted-omega", column(first_seed, scripted)}}},
                        {"reachability", nlohmann::json::array()},
                        {"ceiling", {{"episodes", sac.size()}, {"reached", reached},
                                     {"reached_by_a_controller", reached},
                                     {"reached_only_by_a_schedule", nlohmann::json::array()},
                                     {"reached_by_none", nlohmann::json::array()}}}};
  return {{"rows", {row}}, {"settings", {{"seed", first_seed}}}};
}

}  // namespace

TEST_CASE("merge: two seed sets add up row by row and pair across both", "[runner][merge]") {
  const nlohmann::json a = run(0, {true, false, true, true}, {true, true, true, false}, 4);
  const nlohmann::json b = run(1000, {true, true, false}, {false, true, false}, 2);
  const nlohmann::json m = gw::merge_evaluations({a, b}, {"a.json", "b.json"});
  REQUIRE(m["rows"].size() == 1);
  const nlohmann::json& row = m["rows"][0];
  CHECK(row["episodes"] == 7);
  CHECK(row["wall_time_s"] == 20.0);
  CHECK(row["results"]["sac-policy"]["successes"] == 5);
  CHECK(row["results"]["sac-policy"]["episodes"] == 7);
  CHECK(row["results"]["sac-policy"]["success_rate"] == Approx(5.0 / 7.0));
  CHECK(row["results"]["sac-policy"]["outcomes"]["wrong_branch"] == 2);
  CHECK(row["results"]["scripted-omega"]["results"].size() == 7);
  CHECK(row["ceiling"]["episodes"] == 7);
  CHECK(row["ceiling"]["reached"] == 6);
  CHECK(m["settings"]["merged_from"][1]["run"] == "b.json");
  const std::string md = gw::evaluation_to_markdown(m);
  CHECK(md.find("| coronary-like | 7 | 71% |") != std::string::npos);
  // a: SAC lost seed 1 (scripted won), won seed 3; b: SAC won seed 1000: won 2, lost 1 over both runs.
  CHECK(md.find("| won 2, lost 1 (p 1.00) |") != std::string::npos);
  CHECK(md.find("| 86% (6/7) |") != std::string::npos);
  // Against the paper's 94% of 50 (47; the row carries no paper_episodes, so the paper's table says 50): 71% of
  // 7 (5) is 23 points below, Fisher p 0.11.
  CHECK(md.find("| 94% | -23 points (p 0.11) |") != std::string::npos);
}

TEST_CASE("merge: a small sign-test p keeps its digits", "[runner][merge]") {
  // 10 episodes only SAC reached: p = 2 / 2^10 = 0.002, which two decimals would print as 0.00.
  const std::vector<bool> all(10, true), none(10, false);
  const std::string ten = gw::evaluation_to_markdown(run(0, all, none, 10));
  CHECK(ten.find("| won 10, lost 0 (p 0.002) |") != std::string::npos);
  const std::vector<bool> many(12, true), lost(12, false);
  const nlohmann::json twelve = gw::merge_evaluations({run(0, all, none, 10), run(100, many, lost, 12)}, {"a", "b"});
  CHECK(gw::evaluation_to_markdown(twelve).find("| won 22, lost 0 (p < 0.001) |") != std::string::npos);
}

TEST_CASE("merge: runs that do not fit together are refused by name", "[runner][merge]") {
  const nlohmann::json a = run(0, {true, false}, {true, true}, 2);
  CHECK_THROWS_WITH(gw::merge_evaluations({a, a}, {"a.json", "again.json"}),
                    Catch::Contains("episode coronary T1 seed 0 is in two runs"));
  nlohmann::json other_row = run(10, {true}, {true}, 1);
  other_row["rows"][0]["name"] = "deformed coronary";
  CHECK_THROWS_WITH(gw::merge_evaluations({a, other_row}, {"a.json", "b.json"}),
                    Catch::Contains("row 'deformed coronary' is in b.json but not in a.json"));
  nlohmann::json two_rows = a;
  two_rows["rows"].push_back(other_row["rows"][0]);
  CHECK_THROWS_WITH(gw::merge_evaluations({two_rows, run(20, {true}, {true}, 1)}, {"a.json", "b.json"}),
                    Catch::Contains("row 'deformed coronary' is in a.json but not in b.json"));
  nlohmann::json no_scripted = run(10, {true}, {true}, 1);
  no_scripted["rows"][0]["results"].erase("scripted-omega");
  CHECK_THROWS_WITH(gw::merge_evaluations({a, no_scripted}, {"a.json", "b.json"}),
                    Catch::Contains("no column 'scripted-omega' in b.json"));
  CHECK_THROWS_WITH(gw::merge_evaluations({no_scripted, a}, {"b.json", "a.json"}),
                    Catch::Contains("columns in a.json that b.json lacks"));
  nlohmann::json other_paper = run(10, {true}, {true}, 1);
  other_paper["rows"][0]["paper"] = 0.5;
  CHECK_THROWS_WITH(gw::merge_evaluations({a, other_paper}, {"a.json", "b.json"}),
                    Catch::Contains("different paper figure in b.json"));
  nlohmann::json other_count = run(10, {true}, {true}, 1);
  other_count["rows"][0]["paper_episodes"] = 100;
  CHECK_THROWS_WITH(gw::merge_evaluations({a, other_count}, {"a.json", "b.json"}),
                    Catch::Contains("different paper figure in b.json"));
  CHECK_THROWS(gw::merge_evaluations({}, {}));
}

TEST_CASE("merge: runs under different task settings are different experiments and are refused", "[runner][merge]") {
  const nlohmann::json a = run(0, {true, false}, {true, true}, 2);  // records no speed: it ran the default
  nlohmann::json slow = run(10, {true}, {true}, 1);
  slow["settings"]["push_mm_per_s"] = 5.0;
  CHECK_THROWS_WITH(gw::merge_evaluations({a, slow}, {"a.json", "slow.json"}),
                    Catch::Contains("slow.json ran with push_mm_per_s 5.0, a.json with 10.0"));
  nlohmann::json truth = run(10, {true}, {true}, 1);
  truth["settings"]["centerlines"] = "ground truth";
  CHECK_THROWS_WITH(gw::merge_evaluations({a, truth}, {"a.json", "truth.json"}), Catch::Contains("centerlines"));
  nlohmann::json stiff = run(10, {true}, {true}, 1);
  stiff["settings"]["wire"] = "stiff_tip.json";
  CHECK_THROWS_WITH(gw::merge_evaluations({a, stiff}, {"a.json", "stiff.json"}),
                    Catch::Contains("stiff.json ran with wire \"stiff_tip.json\""));
  // The procedure's settings too: a run with recovery, an assisted one, a tip reshape, a force limit or another junction reading
  // is another experiment than one without.
  for (const auto& [key, value] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"recovery_attempts", 3}, {"recovery_assist", true}, {"reshape_tip_per_mm", 0.3}, {"force_limit_N", 1.5}, {"junctions", "kway"}}) {
    nlohmann::json other = run(10, {true}, {true}, 1);
    other["settings"][key] = value;
    CHECK_THROWS_WITH(gw::merge_evaluations({a, other}, {"a.json", "other.json"}),
                      Catch::Contains("other.json ran with " + key + " " + value.dump()));
    nlohmann::json shard = run(20, {true}, {true}, 1);  // two runs with the same setting join
    shard["settings"][key] = value;
    CHECK(gw::merge_evaluations({other, shard}, {"other.json", "shard.json"})["rows"][0]["episodes"] == 2);
  }
  nlohmann::json same = run(10, {true}, {true}, 1);  // the defaults written out join one that left them out
  same["settings"]["push_mm_per_s"] = 10.0;
  same["settings"]["intermediate_target_mm"] = 50.0;
  const nlohmann::json joined = gw::merge_evaluations({a, same}, {"a.json", "same.json"});
  CHECK(joined["rows"][0]["episodes"] == 3);
  // A joined run carries its inputs' settings and is checked by them in turn.
  CHECK_THROWS_WITH(gw::merge_evaluations({joined, slow}, {"joined.json", "slow.json"}),
                    Catch::Contains("push_mm_per_s"));
  // The Markdown of a run (or a join of runs) at another speed says so above its table; the default's does not.
  nlohmann::json slow2 = run(20, {false}, {true}, 1);
  slow2["settings"]["push_mm_per_s"] = 5.0;
  const std::string md = gw::evaluation_to_markdown(gw::merge_evaluations({slow, slow2}, {"s1", "s2"}));
  CHECK(md.rfind("Insertion speed 5 mm/s (the default, at which the policies were trained, is 10 mm/s).", 0) == 0);
  CHECK(gw::evaluation_to_markdown(joined).find("Insertion speed") == std::string::npos);
}

TEST_CASE("merge: a run written before rows recorded the paper's episode count joins a newer one", "[runner][merge]") {
  // The older run's row has no paper_episodes: the paper's table gives 50 for the coronary row, the
  // count the newer run recorded. The joined row records it.
  const nlohmann::json older = run(0, {true, false}, {true, true}, 2);
  nlohmann::json newer = run(1000, {true, true}, {true, false}, 2);
  newer["rows"][0]["paper_episodes"] = 50;
  for (const auto& runs : {std::vector<nlohmann::json>{older, newer}, std::vector<nlohmann::json>{newer, older}}) {
    const nlohmann::json m = gw::merge_evaluations(runs, {"a.json", "b.json"});
    CHECK(m["rows"][0]["paper_episodes"] == 50);
    CHECK(m["rows"][0]["results"]["sac-policy"]["successes"] == 3);
  }
  newer["rows"][0]["paper_episodes"] = 100;  // a count the paper's table does not give: refused
  CHECK_THROWS_WITH(gw::merge_evaluations({older, newer}, {"a.json", "b.json"}),
                    Catch::Contains("different paper figure in b.json"));
}

TEST_CASE("failure modes: folded losses are counted, and runs that did not record folds are said to", "[runner][merge]") {
  // Seeds 0-3: SAC loses seeds 1 and 3 (both wrong_branch on coronary T1).
  nlohmann::json a = run(0, {true, false, true, false}, {true, true, true, true}, 4);
  nlohmann::json& eps = a["rows"][0]["results"]["sac-policy"]["results"];
  eps[1]["folded"] = true;
  eps[1]["omega_at_loss"] = -0.99;
  eps[3]["folded"] = false;
  eps[3]["omega_at_loss"] = -0.99;
  std::string md = gw::evaluation_to_markdown(a);
  CHECK(md.find("sac-policy: wrong_branch 2 (coronary T1 x2 aimed 2 folded 1)") != std::string::npos);
  // Joined with a run written before "folded" existed: 1 folded of the 2 losses that recorded it.
  nlohmann::json b = run(1000, {false}, {true}, 1);
  b["rows"][0]["results"]["sac-policy"]["results"][0]["omega_at_loss"] = -0.99;
  md = gw::evaluation_to_markdown(gw::merge_evaluations({a, b}, {"a", "b"}));
  CHECK(md.find("sac-policy: wrong_branch 3 (coronary T1 x3 aimed 3 folded 1 of 2)") != std::string::npos);
}

TEST_CASE("merge: a row one run skipped stays skipped, with the reason", "[runner][merge]") {
  nlohmann::json skipped = run(10, {true}, {true}, 1);
  skipped["rows"][0]["skipped"] = "no policy trained on sensitivity/base only";
  skipped["rows"][0]["results"] = nlohmann::json::object();
  const nlohmann::json m = gw::merge_evaluations({run(0, {true}, {true}, 1), skipped}, {"a", "b"});
  CHECK(m["rows"][0]["skipped"] == "no policy trained on sensitivity/base only");
  CHECK(m["rows"][0]["results"].empty());
  CHECK_FALSE(m["rows"][0].contains("ceiling"));
  CHECK(gw::evaluation_to_markdown(m).find("**coronary-like**: skipped: no policy") != std::string::npos);
}

TEST_CASE("merge: a target one run never reached is unreached only if no run's controllers reached it",
          "[runner][merge]") {
  nlohmann::json a = run(0, {false}, {false}, 0);
  a["rows"][0]["reachability"] = {{{"key", "coronary T1"}, {"anatomy", "coronary"}, {"target", 1},
                                   {"reachable", false}}};
  const nlohmann::json reached_later = run(5, {true}, {false}, 1);
  CHECK(gw::merge_evaluations({a, reached_later}, {"a", "b"})["rows"][0]["reachability"].empty());
  nlohmann::json probed_later = run(5, {false}, {false}, 1);
  probed_later["rows"][0]["reachability"] = {{{"key", "coronary T1"}, {"anatomy", "coronary"}, {"target", 1},
                                              {"reachable", true}, {"schedule", "spin+1"}}};
  const nlohmann::json both = gw::merge_evaluations({a, probed_later}, {"a", "b"});
  REQUIRE(both["rows"][0]["reachability"].size() == 1);
  CHECK(both["rows"][0]["reachability"][0]["reachable"] == true);  // one run's schedule reached it
  nlohmann::json no_ceiling = run(5, {true}, {true}, 1);
  no_ceiling["rows"][0].erase("ceiling");
  CHECK_FALSE(gw::merge_evaluations({a, no_ceiling}, {"a", "b"})["rows"][0].contains("ceiling"));
}

TEST_CASE("merge: shards of one run (evaluate --episodes) join into that run", "[runner][merge]") {
  // One run's 3 episodes (seeds 5, 6, 7), as one run and as shards 0:2 and 2:1, each episode with its force.
  auto with_force = [](nlohmann::json run, double first_peak) {
    for (auto& [column, summary] : run["rows"][0]["results"].items()) {
      double peak = first_peak;
      for (nlohmann::json& ep : summary["results"]) {
        ep["force"] = {{"peak_node_N", peak}, {"peak_total_N", 2 * peak}, {"peak_tip_N", 0.1}, {"mean_total_N", 0.3}};
        peak += 1.0;
      }
      summary = gw::summarize_results(summary["results"]);
    }
    return run;
  };
  nlohmann::json whole = with_force(run(5, {true, false, false}, {true, true, false}, 3), 0.5);
  nlohmann::json first = with_force(run(5, {true, false}, {true, true}, 2), 0.5);
  nlohmann::json last = with_force(run(7, {false}, {false}, 1), 2.5);
  // Both shards' ceilings list an episode only a schedule reached, the later shard's first in key order.
  auto reached = [](int target, int seed) { return nlohmann::json{{"anatomy", "coronary"}, {"target", target}, {"seed", seed}}; };
  whole["rows"][0]["ceiling"]["reached_only_by_a_schedule"] = {reached(1, 7), reached(2, 6)};
  first["rows"][0]["ceiling"]["reached_only_by_a_schedule"] = {reached(2, 6)};
  last["rows"][0]["ceiling"]["reached_only_by_a_schedule"] = {reached(1, 7)};
  whole["settings"] = {{"seed", 5}};
  first["settings"] = {{"seed", 5}, {"episodes", {0, 2}}};
  last["settings"] = {{"seed", 5}, {"episodes", {2, 1}}};
  nlohmann::json joined = gw::merge_evaluations({first, last}, {"s0.json", "s2.json"});
  CHECK(joined["settings"] == whole["settings"]);  // the run's own settings, no "merged_from"
  CHECK(joined["rows"][0]["results"] == whole["rows"][0]["results"]);  // force figures too
  CHECK(joined["rows"][0]["results"]["sac-policy"]["force"]["mean_peak_node_N"] == Approx(1.5));
  CHECK(joined["rows"][0]["ceiling"] == whole["rows"][0]["ceiling"]);
  CHECK(gw::evaluation_to_markdown(joined) == gw::evaluation_to_markdown(whole));
  // Runs on different seeds stay a join of runs.
  last["settings"] = {{"seed", 7}, {"episodes", {0, 1}}};
  CHECK(gw::merge_evaluations({first, last}, {"s0.json", "s2.json"})["settings"].contains("merged_from"));
}

TEST_CASE("summary: successes whose peak tip force stayed within 1.5 N, strict and with recovery", "[runner][merge]") {
  auto episode = [](const std::string& outcome, double tip_N, const std::string& recovered, double procedure_tip_N) {
    auto force = [](double tip) {
      return nlohmann::json{{"peak_node_N", tip}, {"peak_total_N", tip}, {"peak_tip_N", tip}, {"mean_total_N", 0.1}};
    };
    return nlohmann::json{{"outcome", outcome}, {"force", force(tip_N)},
                          {"recovery", {{"attempts_allowed", 3}, {"attempts", 1}, {"outcome", recovered},
                                        {"procedure_time_s", 10.0}, {"force", force(procedure_tip_N)}}}};
  };
  const nlohmann::json results = {episode("success", 0.4, "success", 0.4), episode("success", 2.0, "success", 2.0),
                                  episode("wrong_branch", 0.3, "success", 1.2), episode("wrong_branch", 0.3, "success", 1.6),
                                  episode("stuck", 3.0, "stuck", 3.0)};
  const nlohmann::json s = gw::summarize_results(results);
  CHECK(s["successes"] == 2);
  CHECK(s["successes_tip_within_1_5N"] == 1);
  CHECK(s["recovery"]["successes"] == 4);
  CHECK(s["recovery"]["successes_tip_within_1_5N"] == 2);
  CHECK(s["force"]["share_peak_tip_over_1_5N"].get<double>() == Approx(0.4));
}
