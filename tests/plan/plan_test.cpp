// The procedure planner (plan/): it finds plans on a training Y, its plans replay bit for bit through the
// replay controller (what navigate --replay runs), every step stays within the force budget, a search that runs
// out of budget says so with where the tip got, and bad input is refused by name.
#include <catch2/catch.hpp>

#include "engine/wire/wire_params.hpp"
#include "lib/runner/replay_controller.hpp"
#include "lib/runner/row_planned.hpp"
#include "lib/runner/run_episode.hpp"
#include "plan/narrowest_passage.hpp"
#include "plan/plan_json.hpp"
#include "plan/plan_procedure.hpp"
#include "plan/planning_task.hpp"
#include "task/anatomy.hpp"

namespace {

const std::string kT1 = std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y";

const gw::NavigationTask& y_task() {
  static const gw::NavigationTask task = gw::make_navigation_task(
      gw::planning_task_config(gw::TaskConfig{}), gw::default_wire_params(),
      {gw::load_anatomy("t1", kT1 + ".stl", kT1 + ".truth.json")});
  return task;
}

gw::EpisodeTrace replay(const gw::ProcedurePlan& plan, int target, std::uint64_t seed) {
  auto controller = gw::make_replay_controller(gw::plan_actions_from_json(gw::plan_to_json(plan), "plan"));
  return gw::run_episode(y_task(), 0, target, seed, *controller);
}

}  // namespace

TEST_CASE("plan: both targets of a training Y are planned, and each plan replays to the same trajectory", "[plan]") {
  for (const int target : {1, 2}) {
    gw::PlanOptions o;
    o.successes = 1;
    const gw::ProcedurePlan plan = gw::plan_procedure(y_task(), 0, target, 3, o);
    INFO("target " << target << ": " << gw::plan_to_json(plan).dump());
    REQUIRE(plan.kind != gw::PlanKind::kNone);
    CHECK(plan.tip_to_target_mm <= y_task().config.success_radius_mm);
    CHECK(plan.peak_tip_force_N <= o.force_limit_N);
    const gw::EpisodeTrace a = replay(plan, target, 3), b = replay(plan, target, 3);
    CHECK(gw::procedure_outcome(a) == "success");
    REQUIRE(a.time_s.size() == plan.actions.size() + 1);
    REQUIRE(a.tip.size() == b.tip.size());
    for (std::size_t k = 0; k < a.tip.size(); ++k) REQUIRE(a.tip[k] == b.tip[k]);  // bit for bit
    CHECK(a.tip.back() == plan.tip_end);  // the search's own end state, retraced exactly
    for (const double f : a.tip_force_mN) CHECK(f <= 1000.0 * o.force_limit_N);
  }
}

TEST_CASE("plan: the same inputs give the same plan", "[plan]") {
  gw::PlanOptions o;
  o.successes = 1;
  o.max_env_steps = 3000;
  const nlohmann::json a = gw::plan_to_json(gw::plan_procedure(y_task(), 0, 2, 5, o));
  const nlohmann::json b = gw::plan_to_json(gw::plan_procedure(y_task(), 0, 2, 5, o));
  CHECK(a["actions"] == b["actions"]);
  CHECK(a["found"] == b["found"]);
  CHECK(a["tip_end"] == b["tip_end"]);
}

TEST_CASE("plan: a tighter force budget drops the steps above it, and an exhausted budget reports where the tip got",
          "[plan]") {
  gw::PlanOptions o;
  o.max_env_steps = 40;  // 8 maneuvers: far too few to cross the Y
  const gw::ProcedurePlan none = gw::plan_procedure(y_task(), 0, 1, 0, o);
  CHECK(none.kind == gw::PlanKind::kNone);
  CHECK(none.actions.empty());
  CHECK(none.tip_to_target_mm > 10.0);
  CHECK(none.strict.env_steps + none.procedure.env_steps >= 40);
  CHECK(none.tip_end.norm() > 0);
  const nlohmann::json j = gw::plan_to_json(none);
  CHECK(j["found"] == "none");
  CHECK(j["reached"] == false);
  CHECK(j["search"]["strict"]["maneuvers"].get<int>() > 0);

  o.max_env_steps = 20000;
  o.force_limit_N = 1e-6;  // any touch of the wall with the tip is over it
  const gw::ProcedurePlan light = gw::plan_procedure(y_task(), 0, 1, 0, o);
  if (light.kind != gw::PlanKind::kNone)
    for (const double f : replay(light, 1, 0).tip_force_mN) CHECK(f <= 1e-3);
  CHECK(light.strict.over_force + light.procedure.over_force > 0);
}

TEST_CASE("plan: bad input is refused naming the problem", "[plan]") {
  gw::NavigationTask rotation_only = y_task();
  rotation_only.config.action = gw::ActionLayout::kRotation;
  CHECK_THROWS_WITH(gw::plan_procedure(rotation_only, 0, 1, 0), Catch::Contains("act/2"));
  gw::PlanOptions o;
  o.force_limit_N = 0;
  CHECK_THROWS_WITH(gw::plan_procedure(y_task(), 0, 1, 0, o), Catch::Contains("force limit"));
  CHECK_THROWS_WITH(gw::plan_procedure(y_task(), 0, 9, 0), Catch::Contains("target"));
  CHECK_THROWS_WITH(gw::plan_actions_from_json({{"format", "x"}}, "p.json"), Catch::Contains("p.json: not a plan"));
  CHECK_THROWS_WITH(gw::plan_actions_from_json({{"format", gw::kPlanFormat}, {"actions", {{0.5}}}}, "p.json"),
                    Catch::Contains("action 0 is not [rotation, insertion]"));
  CHECK_THROWS_WITH(gw::plan_actions_from_json({{"format", gw::kPlanFormat}, {"actions", {{0.5, 2.0}}}}, "p.json"),
                    Catch::Contains("outside [-1, 1]"));
}

TEST_CASE("plan: a row's planned figure covers every target of its anatomies", "[plan]") {
  gw::PlanOptions o;
  o.successes = 1;
  const nlohmann::json p = gw::row_planned(y_task(), 1, 3, o, "", 2);
  CHECK(p["targets"] == 2);
  CHECK(p["planned"] == 2);
  CHECK(p["strict"].get<int>() <= 2);
  REQUIRE(p["per_target"].size() == 2);
  for (const nlohmann::json& t : p["per_target"]) {
    CHECK(t["anatomy"] == "t1");
    CHECK(t["found"] != "none");
    CHECK(t["seed"] == 3);
    CHECK(t["peak_tip_force_N"].get<double>() <= o.force_limit_N);
  }
  CHECK(p["per_target"][0]["target"] == 1);
  CHECK(p["per_target"][1]["target"] == 2);
  o.max_env_steps = 10;  // nothing can be found: every target says so, with its nearest approach
  const nlohmann::json none = gw::row_planned(y_task(), 2, 0, o, "", 1);
  CHECK(none["planned"] == 0);
  for (const nlohmann::json& t : none["per_target"]) {
    CHECK(t["found"] == "none");
    CHECK(t["seed"] == 1);  // both seeds tried
    CHECK(t["tip_to_target_mm"].get<double>() > 10.0);
  }
}

TEST_CASE("plan: a row's episodes are planned each from its own start, and the columns read against them",
          "[plan]") {
  gw::PlanOptions o;
  o.successes = 1;
  const std::vector<gw::EpisodeRequest> episodes = {{0, 2, 5}, {0, 1, 7}, {0, 2, 9}};
  const nlohmann::json p = gw::episodes_planned(y_task(), episodes, o, "", 2);
  CHECK(p["episodes"] == 3);
  CHECK(p["planned"] == 3);
  REQUIRE(p["per_episode"].size() == 3);
  for (std::size_t k = 0; k < episodes.size(); ++k) {  // in the episodes' order, each from its own seed only
    CHECK(p["per_episode"][k]["target"] == episodes[k].target_id);
    CHECK(p["per_episode"][k]["seed"] == episodes[k].seed);
    CHECK(p["per_episode"][k]["peak_tip_force_N"].get<double>() <= o.force_limit_N);
  }
  CHECK_FALSE(p.contains("per_target"));
  // The same start planned alone gives the same plan (threads do not share anything that changes it).
  const gw::ProcedurePlan alone = gw::plan_procedure(y_task(), 0, 1, 7, o);
  CHECK(p["per_episode"][1]["procedure_time_s"] == alone.time_s);

  // Shards of the row joined (evaluate --from-json): their episodes in order, the counts over all of them.
  nlohmann::json first = p, second = p;
  first["per_episode"].erase(2);
  second["per_episode"].erase(0);
  second["per_episode"].erase(0);
  second["per_episode"][0]["found"] = "none";
  second["per_episode"][0]["why"] = "unreachable: the lumen narrows";
  const nlohmann::json joined = gw::join_episodes_planned({&first, &second});
  CHECK(joined["episodes"] == 3);
  CHECK(joined["planned"] == 2);
  CHECK(joined["unreachable"] == 1);
  CHECK(joined["per_episode"][1] == p["per_episode"][1]);
  CHECK(joined["per_episode"][2]["seed"] == 9);

  // A column's episodes matched to the plans by anatomy, target and seed; an episode not planned is not counted.
  nlohmann::json planned = p;
  planned["per_episode"][2]["found"] = "none";
  auto episode = [](int target, int seed, const std::string& outcome) {
    return nlohmann::json{{"anatomy", "t1"}, {"target", target}, {"seed", seed}, {"outcome", outcome}};
  };
  const nlohmann::json results = {
      {"sac-policy", {{"results", {episode(2, 5, "success"), episode(1, 7, "wrong_branch"), episode(2, 9, "success"),
                                   episode(1, 11, "success")}}}}};
  const nlohmann::json c = gw::planned_against_columns(planned, results)["sac-policy"];
  CHECK(c["episodes"] == 3);
  CHECK(c["reached"] == 2);
  CHECK(c["planned"] == 2);
  CHECK(c["reached_and_planned"] == 1);
  CHECK(c["planned_not_reached"] == 1);  // seed 7: a plan exists, the controller entered the wrong branch
  CHECK(c["reached_not_planned"] == 1);  // seed 9: the controller reached what the planner did not
}

TEST_CASE("plan: the narrowest passage of a course is found where the lumen is narrower than the wire", "[plan]") {
  gw::CenterlineGraph g;  // one straight branch along z, 0.5 mm point spacing, 40 mm
  g.branches.push_back({0, -1, {}, {}});
  for (int k = 0; k <= 80; ++k) {
    g.branches[0].points.emplace_back(0.0, 0.0, 0.5 * k);
    g.branches[0].radii.push_back(k >= 40 && k <= 46 ? 0.1 : 1.5);  // 20-23 mm: 0.1 mm, a 3 mm stretch
  }
  g.inlet = {0, Eigen::Vector3d::Zero(), 0, 1.5};
  g.targets.push_back({1, Eigen::Vector3d(0, 0, 40), 0, 1.5});
  const auto passage = gw::narrowest_passage(g, 1, 0.178);
  REQUIRE(passage);
  CHECK(passage->start_mm == Approx(20.0));
  CHECK(passage->length_mm == Approx(3.0));
  CHECK(passage->radius_mm == Approx(0.1));
  CHECK_FALSE(gw::narrowest_passage(g, 1, 0.05));           // a thinner wire passes
  CHECK_FALSE(gw::narrowest_passage(g, 1, 0.178, 3.5));     // shorter than the least length that counts
  g.branches[0].radii.assign(81, 1.5);
  g.branches[0].radii[60] = 0.01;                           // one dipping point is not a wall across the lumen
  CHECK_FALSE(gw::narrowest_passage(g, 1, 0.178));
  CHECK_THROWS_WITH(gw::narrowest_passage(g, 2, 0.178), Catch::Contains("target"));
}

TEST_CASE("plan: a target behind a lumen narrower than the wire is reported unreachable, with the reason, at once",
          "[plan]") {
  // The training Y with its second branch's lumen narrowed, over 4 mm, below the 0.014" wire's radius (0.178 mm).
  gw::Anatomy narrowed = gw::load_anatomy("t1", kT1 + ".stl", kT1 + ".truth.json");
  const int branch = narrowed.graph.targets[1].branch;
  std::vector<double>& radii = narrowed.graph.branches[static_cast<std::size_t>(branch)].radii;
  const std::size_t mid = radii.size() / 2;
  for (std::size_t k = mid; k < mid + 20 && k < radii.size(); ++k) radii[k] = 0.12;
  const gw::NavigationTask task =
      gw::make_navigation_task(gw::planning_task_config(gw::TaskConfig{}), gw::default_wire_params(), {narrowed});
  const gw::ProcedurePlan plan = gw::plan_procedure(task, 0, 2, 0);
  CHECK(plan.kind == gw::PlanKind::kNone);
  CHECK(plan.strict.env_steps == 0);  // nothing searched: no budget spent on it
  CHECK_THAT(plan.why, Catch::StartsWith("unreachable: the lumen narrows to 0.120 mm radius"));
  CHECK_THAT(plan.why, Catch::Contains("below the wire's radius 0.178 mm"));
  CHECK(gw::plan_to_json(plan)["why"] == plan.why);
  CHECK(gw::plan_procedure(task, 0, 1, 0, {}).kind != gw::PlanKind::kNone);  // the other branch is untouched
  const nlohmann::json row = gw::row_planned(task, 1, 0, {}, "", 1);
  CHECK(row["unreachable"] == 1);
  CHECK(row["per_target"][1]["why"] == plan.why);
}

TEST_CASE("plan: a search that runs out of ways forward says so, and one that runs out of budget says that", "[plan]") {
  gw::PlanOptions o;
  o.strict_only = true;
  o.max_env_steps = 40;
  const gw::ProcedurePlan spent = gw::plan_procedure(y_task(), 0, 1, 0, o);
  CHECK_FALSE(spent.strict.exhausted);
  CHECK_THAT(spent.why, Catch::StartsWith("budget spent: "));
  CHECK_THAT(spent.why, Catch::Contains("not a proof"));
  o.max_env_steps = 20000;
  o.hold_steps = 100;      // one maneuver pushes 40 mm: into the fork and past it
  o.force_limit_N = 1e-6;  // and any touch of the wall with the tip is over the budget
  const gw::ProcedurePlan boxed = gw::plan_procedure(y_task(), 0, 1, 0, o);
  INFO(boxed.why);
  CHECK(boxed.kind == gw::PlanKind::kNone);
  CHECK(boxed.strict.exhausted);
  CHECK(boxed.strict.env_steps < o.max_env_steps);
  CHECK_THAT(boxed.why, Catch::StartsWith("search exhausted: "));
  CHECK(gw::plan_to_json(boxed)["search"]["strict"]["exhausted"] == true);
}

TEST_CASE("plan: a guide that reaches the target gives a plan that replays, one that enters the wrong branch is dropped",
          "[plan][guide]") {
  // Guides: the scripted rule as it is (it aims away from the wrong branch, turning one way) and an "anti-rule"
  // that turns the tip at the wrong branch and holds it there. Seed 3, both targets of the training Y.
  auto rule = [](double turn) {
    return gw::PlanGuide{"rule", [turn](const gw::Observation& obs) {
                           return gw::Action{obs[gw::obs_index::kOmega] > -0.95 ? turn : 0.0, 1.0};
                         }, {}};
  };
  gw::PlanGuide wrong{"aim-at-wrong", [](const gw::Observation& obs) {
                        return gw::Action{obs[gw::obs_index::kOmega] < 0.95 ? 1.0 : 0.0, 1.0};
                      }, {}};
  int begun = 0;
  wrong.begin = [&begun] { ++begun; };
  for (const int target : {1, 2}) {
    gw::PlanOptions o;
    o.successes = 1;
    o.strict_only = true;
    o.guides = {wrong, rule(1.0)};
    const gw::ProcedurePlan plan = gw::plan_procedure(y_task(), 0, target, 3, o);
    INFO("target " << target << ": " << gw::plan_to_json(plan).dump().substr(0, 600));
    REQUIRE(plan.kind == gw::PlanKind::kStrict);
    CHECK(plan.guide == "rule");  // the first plan found was the rule's: the search did not run
    CHECK(plan.strict.guided == 1);
    CHECK(plan.strict.maneuvers == 0);
    CHECK(plan.strict.wrong_branch == 1);  // the anti-rule's episode, dropped at the wrong branch
    CHECK(gw::plan_to_json(plan)["guide"] == "rule");
    const gw::EpisodeTrace a = replay(plan, target, 3);
    CHECK(gw::procedure_outcome(a) == "success");
    REQUIRE(a.time_s.size() == plan.actions.size() + 1);
    CHECK(a.tip.back() == plan.tip_end);
  }
  CHECK(begun == 2);
  gw::PlanOptions none;
  none.successes = 1;
  none.strict_only = true;
  const gw::ProcedurePlan searched = gw::plan_procedure(y_task(), 0, 1, 3, none);
  CHECK(searched.guide.empty());
  CHECK(searched.strict.guided == 0);
}

TEST_CASE("plan: from a lead-in, the search starts 1 s before the controller's deepest step and the plan replays",
          "[plan][lead-in]") {
  // The lead-in: a hand that pushes for 60 steps and then pulls back until its episode ends (stuck or wire out);
  // the plan starts with its steps up to 25 before its deepest along the course.
  int step = 0;
  gw::PlanGuide give_up{"give-up", [&step](const gw::Observation&) {
                          return gw::Action{0.0, ++step <= 60 ? 1.0 : -1.0};
                        }, [&step] { step = 0; }};
  gw::PlanOptions o;
  o.successes = 1;
  o.lead_in = give_up;
  const gw::ProcedurePlan plan = gw::plan_procedure(y_task(), 0, 2, 3, o);
  INFO(gw::plan_to_json(plan).dump().substr(0, 900));
  REQUIRE(plan.lead_in);
  CHECK(plan.lead_in->controller == "give-up");
  CHECK(plan.lead_in->outcome != "success");
  CHECK(plan.lead_in->deepest_step > 50);
  CHECK(plan.lead_in->deepest_step <= 61);
  CHECK(plan.lead_in->ran > plan.lead_in->deepest_step);
  CHECK(plan.lead_in->steps == plan.lead_in->deepest_step - o.lead_in_back_steps);
  REQUIRE(plan.kind != gw::PlanKind::kNone);
  REQUIRE(plan.actions.size() > static_cast<std::size_t>(plan.lead_in->steps));
  for (int k = 0; k < plan.lead_in->steps; ++k) CHECK(plan.actions[static_cast<std::size_t>(k)].insertion == 1.0);
  const nlohmann::json j = gw::plan_to_json(plan);
  CHECK(j["lead_in"]["steps"] == plan.lead_in->steps);
  const gw::EpisodeTrace a = replay(plan, 2, 3);  // from the reset: the lead-in's steps, then the search's
  CHECK(gw::procedure_outcome(a) == "success");
  REQUIRE(a.time_s.size() == plan.actions.size() + 1);
  CHECK(a.tip.back() == plan.tip_end);
  // A lead-in that reaches the target within the budget is the plan: its whole episode, nothing searched.
  gw::PlanOptions reach;
  reach.lead_in = gw::PlanGuide{"rule", [](const gw::Observation& obs) {
                                  return gw::Action{obs[gw::obs_index::kOmega] > -0.95 ? 1.0 : 0.0, 1.0};
                                }, {}};
  const gw::ProcedurePlan own = gw::plan_procedure(y_task(), 0, 2, 3, reach);
  REQUIRE(own.lead_in);
  CHECK(own.lead_in->outcome == "success");
  CHECK(own.lead_in->steps == own.lead_in->ran);
  CHECK(own.steps == own.lead_in->ran);
  CHECK(own.kind == gw::PlanKind::kStrict);
  CHECK(own.guide == "rule");
  CHECK(own.strict.env_steps == 0);
  CHECK(gw::procedure_outcome(replay(own, 2, 3)) == "success");
  o.lead_in_back_steps = -1;
  CHECK_THROWS_WITH(gw::plan_procedure(y_task(), 0, 2, 3, o), Catch::Contains("back_steps"));
}
