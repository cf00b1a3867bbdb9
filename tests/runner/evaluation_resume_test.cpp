// evaluate's progress line (ETA) and --resume: each finished row handed to the caller at once, and a
// run resumed from what an interrupted run wrote equal to an uninterrupted one.
#include <catch2/catch.hpp>
#include <stdexcept>

#include "lib/runner/controller.hpp"
#include "lib/runner/evaluation_progress.hpp"
#include "lib/runner/evaluation_table.hpp"

namespace {

// Two one-anatomy rows, 2 push-only episodes each, ground-truth centerlines: seconds, no CGAL.
gw::EvaluationOptions tiny_options() {
  gw::EvaluationOptions o;
  o.index_path = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";
  o.controllers = {"push-only"};
  o.extract_centerlines = false;
  o.episode_scale = 0.02;
  o.reachability_seeds = 0;
  o.seed = 11;
  return o;
}

const std::vector<gw::EvaluationRow> kRows = {{"t1", {"t1_straight_y"}, 100, 0.95, false},
                                              {"t2", {"t2_curved_straight_exit"}, 100, 0.95, false}};

// The evaluation without the rows' wall times (the only field that differs between equal runs).
nlohmann::json without_wall_times(nlohmann::json e) {
  for (nlohmann::json& row : e["rows"]) row.erase("wall_time_s");
  return e;
}

struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace

TEST_CASE("evaluate progress: durations and the ETA as printed", "[runner]") {
  CHECK(gw::format_duration(0.4) == "0s");
  CHECK(gw::format_duration(59.9) == "59s");
  CHECK(gw::format_duration(185) == "3m05s");
  CHECK(gw::format_duration(3720) == "1h02m");
  CHECK(gw::progress_text(0, 10, 3) == "0/10 episodes, 3s elapsed, ETA ?");
  CHECK(gw::progress_text(5, 20, 50) == "5/20 episodes, 50s elapsed, ETA 2m30s");  // 10 s an episode, 15 left
  CHECK(gw::progress_text(20, 20, 50) == "20/20 episodes, 50s elapsed, ETA 0s");
  gw::ProgressMeter meter(6, nullptr, false);  // silent: counts only
  meter.episode_done("a");
  meter.episode_done("b");
  meter.drop(3);  // a skipped row's episodes
  CHECK(meter.done() == 2);
  CHECK(meter.total() == 3);
  meter.drop(5);  // never below what was done
  CHECK(meter.total() == 2);
}

TEST_CASE("evaluate --resume: the rows an interrupted run wrote are kept, the others run, and the table equals an "
          "uninterrupted run",
          "[runner]") {
  gw::EvaluationOptions o = tiny_options();
  int rows_written = 0;
  o.on_row = [&](const nlohmann::json& so_far) {
    ++rows_written;
    CHECK(so_far["rows"].size() == static_cast<std::size_t>(rows_written));  // every finished row, at once
    CHECK(so_far["settings"] == gw::evaluation_settings(o));
  };
  const nlohmann::json full = gw::run_evaluation(kRows, o);
  REQUIRE(rows_written == 2);
  REQUIRE(full["rows"].size() == 2);
  REQUIRE(full["rows"][0]["results"]["push-only"]["episodes"] == 2);
  CHECK(full["settings"]["controllers"] == nlohmann::json::array({"push-only"}));

  // Interrupted after the first row: what the caller wrote holds it.
  nlohmann::json written;
  o.on_row = [&](const nlohmann::json& so_far) {
    written = so_far;
    throw Interrupted();
  };
  CHECK_THROWS_AS(gw::run_evaluation(kRows, o), Interrupted);
  REQUIRE(written["rows"].size() == 1);
  CHECK(written["rows"][0]["name"] == "t1");

  // Resumed: t1 is kept as written (its wall time too: not run again), only t2 runs.
  o.finished_rows = gw::resumable_rows(written, o);
  REQUIRE(o.finished_rows.size() == 1);
  std::vector<std::string> ran;
  o.on_row = [&](const nlohmann::json& so_far) { ran.push_back(so_far["rows"].back()["name"].get<std::string>()); };
  const nlohmann::json resumed = gw::run_evaluation(kRows, o);
  CHECK(ran == std::vector<std::string>{"t2"});
  CHECK(resumed["rows"][0]["wall_time_s"] == written["rows"][0]["wall_time_s"]);
  CHECK(without_wall_times(resumed) == without_wall_times(full));  // same seeds, same episodes

  // A finished table resumed runs nothing and stays the same.
  o.finished_rows = gw::resumable_rows(full, o);
  ran.clear();
  CHECK(gw::run_evaluation(kRows, o) == full);
  CHECK(ran.empty());
}

TEST_CASE("evaluate --resume refuses an earlier run of other settings and runs its skipped rows again", "[runner]") {
  const gw::EvaluationOptions o = tiny_options();
  nlohmann::json previous = {{"rows", {{{"name", "t1"}}, {{"name", "t2"}, {"skipped", "mesh missing"}}}},
                             {"settings", gw::evaluation_settings(o)}};
  const nlohmann::json kept = gw::resumable_rows(previous, o);
  REQUIRE(kept.size() == 1);
  CHECK(kept[0]["name"] == "t1");

  gw::EvaluationOptions other_seed = o;
  other_seed.seed = 12;
  CHECK_THROWS_WITH(gw::resumable_rows(previous, other_seed), Catch::Contains("seed was 11") &&
                                                                   Catch::Contains("this run's is 12"));
  gw::EvaluationOptions more_columns = o;
  more_columns.controllers = {"push-only", "scripted-omega"};
  CHECK_THROWS_WITH(gw::resumable_rows(previous, more_columns), Catch::Contains("controllers"));
  previous["settings"].erase("controllers");  // a results.json written before evaluate recorded them
  CHECK_THROWS_WITH(gw::resumable_rows(previous, o), Catch::Contains("controllers was not recorded"));
  const nlohmann::json joined = {{"rows", nlohmann::json::array()},
                                 {"settings", {{"merged_from", nlohmann::json::array({{{"run", "a.json"}}})}}}};
  CHECK_THROWS_WITH(gw::resumable_rows(joined, o), Catch::Contains("joins several runs"));
}

TEST_CASE("evaluate records the shipped files' paths relative to the source tree, and resumes a run that named them "
          "absolutely",
          "[runner]") {
  const std::string source = GW_SOURCE_DIR;
  CHECK(gw::recorded_path(source + "/policy/trained/sac_actor.json") == "policy/trained/sac_actor.json");
  CHECK(gw::recorded_path(source + "/engine/wire/../wire/coronary_014.json") == "engine/wire/coronary_014.json");
  CHECK(gw::recorded_path("/elsewhere/actor.json") == "/elsewhere/actor.json");    // the user's own file: as given
  CHECK(gw::recorded_path(source + "_other/actor.json") == source + "_other/actor.json");  // a sibling, not inside
  CHECK(gw::recorded_path("runs/actor.json") == "runs/actor.json");               // relative: as given
  CHECK(gw::recorded_path("") == "");

  gw::EvaluationOptions o = tiny_options();
  o.policy = gw::shipped_path("policy/trained/sac_actor.json");
  o.base_policy = gw::base_policy_path(o.policy);
  o.wire_path = gw::shipped_path("engine/wire/coronary_014.json");
  const nlohmann::json settings = gw::evaluation_settings(o);
  CHECK(settings["policy"] == "policy/trained/sac_actor.json");
  CHECK(settings["base_policy"] == "policy/trained/sac_actor_base.json");
  CHECK(settings["wire"] == "engine/wire/coronary_014.json");

  nlohmann::json previous = {{"rows", {{{"name", "t1"}}}}, {"settings", settings}};
  previous["settings"]["policy"] = o.policy;  // as evaluate wrote it before
  previous["settings"]["base_policy"] = o.base_policy;
  previous["settings"]["wire"] = o.wire_path;
  CHECK(gw::resumable_rows(previous, o).size() == 1);
  previous["settings"]["policy"] = "/elsewhere/actor.json";
  CHECK_THROWS_WITH(gw::resumable_rows(previous, o), Catch::Contains("policy was \"/elsewhere/actor.json\""));
}
