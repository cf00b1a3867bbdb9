// What navigate and evaluate share: planning batches (--target N|all|random), running them on
// threads with the same result as one thread, the JSON summary, output files, and the table.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "lib/report/trace_json.hpp"
#include "lib/runner/controller.hpp"
#include "lib/runner/episode_batch.hpp"
#include "lib/runner/evaluation_table.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "lib/runner/navigation_outputs.hpp"
#include "lib/runner/reachability.hpp"
#include "lib/runner/rotation_schedules.hpp"
#include "lib/runner/run_episode.hpp"
#include "lib/runner/success_statistics.hpp"
#include "engine/scene/moving_wall.hpp"
#include "engine/scene/wall_motion.hpp"
#include "task/navigation_task.hpp"
#include "task/observation.hpp"
#include "engine/wire/wire_params.hpp"
#include "tests/runner/aim_controllers.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kT1 = std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y";

// t1 with its ground-truth centerline (no CGAL in the loop) and a short step limit, so episodes
// end by truncation after a second of wall time.
struct ShortT1 {
  gw::NavigationAnatomy nav;
  gw::NavigationTask task;
  explicit ShortT1(int max_steps = 25)
      : nav(gw::load_navigation_anatomy(kT1 + ".stl", {1.0, std::nullopt, kT1 + ".truth.json", false})),
        task(gw::make_navigation_task(config(max_steps), gw::default_wire_params(), {nav.anatomy})) {}
  static gw::TaskConfig config(int max_steps) {
    gw::TaskConfig c;
    c.max_steps = max_steps;
    return c;
  }
};

fs::path scratch_dir(const std::string& name) {
  const fs::path d = fs::path(GW_BINARY_DIR) / "test_runner_scratch" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST_CASE("navigate's inlet: --inlet, else the mesh's truth sidecar, else the widest end with a warning", "[runner]") {
  const gw::CenterlineGraph truth = gw::read_centerline(kT1 + ".truth.json");
  gw::NavigationAnatomyOptions options;
  options.use_cache = false;
  // t1 is a Y of constant radius: its three ends are equally wide.
  const gw::NavigationAnatomy beside_truth = gw::load_navigation_anatomy(kT1 + ".stl", options);
  CHECK(beside_truth.inlet_source == kT1 + ".truth.json");
  CHECK(beside_truth.inlet_warning.empty());
  CHECK((beside_truth.anatomy.graph.inlet.position - truth.inlet.position).norm() < 1.0);
  REQUIRE(beside_truth.anatomy.graph.targets.size() == truth.targets.size());
  for (size_t k = 0; k < truth.targets.size(); ++k)
    CHECK((beside_truth.anatomy.graph.targets[k].position - truth.targets[k].position).norm() < 1.0);

  const fs::path alone = scratch_dir("inlet") / "t1_copy.stl";
  fs::copy_file(kT1 + ".stl", alone);
  const gw::NavigationAnatomy guessed = gw::load_navigation_anatomy(alone.string(), options);
  CHECK(guessed.inlet_source == "widest end");
  CHECK(guessed.inlet_warning.find("pass --inlet") != std::string::npos);

  options.inlet = truth.inlet.position;
  const gw::NavigationAnatomy given = gw::load_navigation_anatomy(alone.string(), options);
  CHECK(given.inlet_source == "--inlet");
  CHECK(given.inlet_warning.empty());
  CHECK((given.anatomy.graph.inlet.position - truth.inlet.position).norm() < 1.0);
}

TEST_CASE("plan_episodes: targets and seeds of a batch", "[runner]") {
  const ShortT1 t1;
  REQUIRE(t1.nav.anatomy.graph.targets.size() == 2);

  const auto one = gw::plan_episodes(t1.task, 0, "2", 3, 10);
  REQUIRE(one.size() == 3);
  for (std::size_t k = 0; k < one.size(); ++k) {
    CHECK(one[k].target_id == 2);
    CHECK(one[k].seed == 10 + k);  // episode k of a batch is re-run alone with --seed S+k
  }

  const auto all = gw::plan_episodes(t1.task, 0, "all", 2, 0);
  REQUIRE(all.size() == 4);
  CHECK(all[0].target_id == 1);
  CHECK(all[1].target_id == 1);
  CHECK(all[2].target_id == 2);
  CHECK(all[3].seed == 3);

  const auto random_a = gw::plan_episodes(t1.task, 0, "random", 40, 7);
  const auto random_b = gw::plan_episodes(t1.task, 0, "random", 40, 7);
  int ones = 0;
  for (std::size_t k = 0; k < random_a.size(); ++k) {
    CHECK(random_a[k].target_id == random_b[k].target_id);
    CHECK((random_a[k].target_id == 1 || random_a[k].target_id == 2));
    ones += random_a[k].target_id == 1;
  }
  CHECK(ones > 5);  // both targets drawn
  CHECK(ones < 35);
}

TEST_CASE("plan_episodes: unknown targets and bad counts are clear errors", "[runner]") {
  const ShortT1 t1;
  CHECK_THROWS_WITH(gw::plan_episodes(t1.task, 0, "3", 1, 0),
                    Catch::Contains("target 3 does not exist") && Catch::Contains("1..2"));
  CHECK_THROWS_WITH(gw::plan_episodes(t1.task, 0, "0", 1, 0), Catch::Contains("does not exist"));
  CHECK_THROWS_WITH(gw::plan_episodes(t1.task, 0, "two", 1, 0), Catch::Contains("'two' is not a number"));
  CHECK_THROWS_WITH(gw::plan_episodes(t1.task, 0, "1x", 1, 0), Catch::Contains("not a number"));
  CHECK_THROWS_WITH(gw::plan_episodes(t1.task, 0, "1", 0, 0), Catch::Contains("at least 1"));
  CHECK_THROWS_AS(gw::plan_episodes(t1.task, 1, "1", 1, 0), std::invalid_argument);
}

TEST_CASE("controllers: names and missing policy files", "[runner]") {
  CHECK(gw::make_controller("push-only", "")->act(gw::Observation{}).rotation == 0.0);
  CHECK_THROWS_WITH(gw::make_controller("pid", ""), Catch::Contains("'pid'"));
  CHECK_THROWS_WITH(gw::make_controller("pid", ""), Catch::Contains("spin+1"));
  // A rotation schedule is a controller too; reused across a batch, it restarts with each episode.
  auto wiggle = gw::make_controller("wiggle", "");
  CHECK(wiggle->name() == "wiggle");
  wiggle->act(gw::Observation{});
  CHECK(wiggle->act(gw::Observation{}).rotation != 0.0);
  wiggle->begin_episode();
  CHECK(wiggle->act(gw::Observation{}).rotation == 0.0);
  CHECK_THROWS_WITH(gw::make_controller("policy", "/nonexistent/actor.json"),
                    Catch::Contains("/nonexistent/actor.json"));
}

// A linear `inputs` -> 1 actor recorded with `layout`.
static std::string write_actor(const fs::path& dir, const std::string& layout, int inputs = 11) {
  std::string weights = "0";
  for (int i = 1; i < inputs; ++i) weights += ", 0";
  const std::string n = std::to_string(inputs);
  const fs::path p = dir / "actor.json";
  std::ofstream(p) << R"({"format": "guidewire-nav/actor/1", "obs_size": )" + n +
                          R"(, "action_size": 1, "obs_layout": ")" + layout + R"(", "obs_normalization": null,
    "layers": [{"shape": [1, )" + n + R"(], "weight": [)" + weights + R"(], "bias": [0.5], "activation": "identity"}],
    "output": {"squash": "tanh", "low": [-1], "high": [1]}, "training_settings": {}, "git_commit": null})";
  return p.string();
}

TEST_CASE("controllers: an actor gets the omega it was trained with, an unknown layout is refused", "[runner]") {
  const fs::path dir = scratch_dir("layouts");
  gw::TaskConfig config;
  REQUIRE(config.observation.omega_plane == gw::OmegaPlane::kApproach);
  gw::make_controller("policy", write_actor(dir, "guidewire-nav/obs/1"))->adapt(config);
  CHECK(config.observation.omega_plane == gw::OmegaPlane::kCorrectBranch);
  CHECK_FALSE(config.observation.omega_side);
  gw::make_controller("policy", write_actor(dir, "guidewire-nav/obs/3", 12))->adapt(config);
  CHECK(config.observation.omega_plane == gw::OmegaPlane::kApproach);
  CHECK(config.observation.omega_side);
  gw::make_controller("policy", write_actor(dir, "guidewire-nav/obs/1"))->adapt(config);
  CHECK_FALSE(config.observation.omega_side);
  config.observation.omega_plane = gw::OmegaPlane::kCorrectBranch;
  gw::make_controller("scripted-omega", "")->adapt(config);  // baselines leave the config alone
  CHECK(config.observation.omega_plane == gw::OmegaPlane::kCorrectBranch);
  CHECK_THROWS_WITH(gw::make_controller("policy", write_actor(dir, "guidewire-nav/obs/0")),
                    Catch::Contains("guidewire-nav/obs/0") && Catch::Contains("guidewire-nav/obs/3"));
  // a retired layout is an unknown one (docs/policy_history.md)
  CHECK_THROWS_WITH(gw::make_controller("policy", write_actor(dir, "guidewire-nav/obs/2")),
                    Catch::Contains("unknown observation"));
  // The input count must be the layout's: obs/3 has omega's sine as a twelfth entry.
  CHECK_THROWS_WITH(gw::make_controller("policy", write_actor(dir, "guidewire-nav/obs/3", 11)),
                    Catch::Contains("takes 11") && Catch::Contains("has 12"));
  CHECK_THROWS_WITH(gw::make_controller("policy", write_actor(dir, "guidewire-nav/obs/1", 12)),
                    Catch::Contains("takes 12") && Catch::Contains("has 11"));
}

TEST_CASE("run_batch: threads give the same episodes as one thread, and the summary counts them", "[runner]") {
  const ShortT1 t1;
  const auto requests = gw::plan_episodes(t1.task, 0, "all", 2, 5);
  auto scripted = [] { return gw::make_scripted_omega_controller(); };
  gw::TraceOptions options;
  options.wire_shape_every = 10;
  int calls = 0;
  const auto serial = gw::run_batch(t1.task, requests, scripted, 1, options, [&](int done, int total) {
    ++calls;
    CHECK(done <= total);
  });
  CHECK(calls == 4);
  const auto threaded = gw::run_batch(t1.task, requests, scripted, 3, options);
  REQUIRE(serial.size() == 4);
  REQUIRE(threaded.size() == 4);
  for (std::size_t k = 0; k < serial.size(); ++k) {
    CHECK(serial[k].seed == requests[k].seed);
    CHECK(serial[k].target_id == requests[k].target_id);
    CHECK(serial[k].outcome == "timeout");  // 25 steps cannot reach a target 60+ mm away
    CHECK(serial[k].time_s.size() == 26);   // the reset frame and 25 steps
    REQUIRE(serial[k].tip.size() == threaded[k].tip.size());
    CHECK(serial[k].tip.back() == threaded[k].tip.back());  // bit for bit
    CHECK(serial[k].action == threaded[k].action);
    CHECK(serial[k].wire_shapes.size() >= 3);
    // What the controller saw, frame by frame: the observation carries the action just applied.
    REQUIRE(serial[k].observation.size() == serial[k].time_s.size());
    REQUIRE(serial[k].observation_names.size() == serial[k].observation[0].size());
    CHECK(serial[k].observation_names[gw::obs_index::kAction] == std::string("action"));
    for (std::size_t f = 1; f < serial[k].time_s.size(); ++f)
      CHECK(serial[k].observation[f][gw::obs_index::kAction] == serial[k].action[f]);
    CHECK(serial[k].goal == std::vector<int>(serial[k].time_s.size(), 0));
  }
  // different seeds start with a different wire rotation
  CHECK(serial[0].tip.back() != serial[1].tip.back());
  // A stateful controller reused by one thread starts every episode afresh: same seed, same actions.
  const std::vector<gw::EpisodeRequest> twice = {{0, 1, 9}, {0, 1, 9}};
  const auto wiggles = gw::run_batch(t1.task, twice, [] { return gw::make_controller("wiggle", ""); }, 1, options);
  CHECK(wiggles[0].action == wiggles[1].action);
  CHECK(wiggles[0].tip.back() == wiggles[1].tip.back());

  const nlohmann::json summary = gw::summarize_episodes(serial);
  CHECK(summary["episodes"] == 4);
  CHECK(summary["successes"] == 0);
  CHECK(summary["outcomes"]["timeout"] == 4);
  CHECK(summary["outcomes"]["success"] == 0);
  CHECK(summary["results"][2]["target"] == 2);
  CHECK(summary["results"][2]["steps"] == 25);
}

TEST_CASE("a step time limit ends the episode at the first step past it as a timeout naming the limit, and none is the default",
          "[runner]") {
  const ShortT1 t1;
  gw::TraceOptions options;
  CHECK(options.step_time_limit_s == 0.0);
  auto scripted = gw::make_scripted_omega_controller();
  options.step_time_limit_s = 1e-12;  // any env step runs longer
  const gw::EpisodeTrace cut = gw::run_episode(t1.task, 0, 1, 5, *scripted, options);
  CHECK(cut.outcome == "timeout");
  CHECK(cut.detail.find("time limit") != std::string::npos);
  CHECK(cut.time_s.size() == 2);  // the reset frame and the one step that ran past the limit
  options.step_time_limit_s = 0.0;
  const gw::EpisodeTrace whole = gw::run_episode(t1.task, 0, 1, 5, *scripted, options);
  CHECK(whole.outcome == "timeout");
  CHECK(whole.detail == "step limit reached");
  CHECK(whole.time_s.size() == 26);
}

TEST_CASE("a wrong branch records omega when the tip reached the lost bifurcation", "[runner]") {
  const ShortT1 t1(0);  // automatic step limit: episodes end at a branch
  const std::vector<gw::EpisodeRequest> requests = {{0, 1, 3}, {0, 2, 4}};
  const auto wrong = gw::run_batch(t1.task, requests, [] { return std::make_unique<gwtest::AimAtWrongBranch>(); }, 1, {});
  const auto right = gw::run_batch(t1.task, requests, [] { return gw::make_scripted_omega_controller(); }, 1, {});
  for (std::size_t k = 0; k < requests.size(); ++k) {
    REQUIRE(wrong[k].outcome == "wrong_branch");
    CHECK(wrong[k].omega_at_loss > 0.9);  // it was aimed at the wrong branch, and the report can tell
    REQUIRE(right[k].outcome == "success");
    CHECK(std::isnan(right[k].omega_at_loss));
  }
  const nlohmann::json summary = gw::summarize_episodes(wrong);
  CHECK(summary["results"][0]["omega_at_loss"].get<double>() == wrong[0].omega_at_loss);
  CHECK_FALSE(gw::summarize_episodes(right)["results"][0].contains("omega_at_loss"));
  // The trajectory file keeps it; a success's file has none.
  const gw::EpisodeTrace back = gw::trace_from_json(gw::trace_to_json(wrong[0]), "test");
  CHECK(back.omega_at_loss == Approx(wrong[0].omega_at_loss));
  CHECK(std::isnan(gw::trace_from_json(gw::trace_to_json(right[0]), "test").omega_at_loss));
}

TEST_CASE("a loss where the tip folded over first is told apart from an aimed one", "[runner]") {
  // Synthetic traces: 2 s of frames every 40 ms, theta_t_1 = 0.9 except where set.
  auto trace = [](const std::string& outcome, double fold_at_s) {
    gw::EpisodeTrace t;
    t.outcome = outcome;
    for (int f = 0; f <= 50; ++f) {
      t.time_s.push_back(0.04 * f);
      std::vector<double> obs(gw::kObservationSize, 0.0);
      obs[gw::obs_index::kTheta] = std::abs(0.04 * f - fold_at_s) < 0.02 ? -0.98 : 0.9;
      t.observation.push_back(obs);
    }
    return t;
  };
  CHECK(gw::tip_folded_before_loss(trace("wrong_branch", 1.6)));        // 0.4 s before the loss
  CHECK_FALSE(gw::tip_folded_before_loss(trace("wrong_branch", 0.4)));  // 1.6 s before: not this loss
  CHECK_FALSE(gw::tip_folded_before_loss(trace("wrong_branch", -1)));   // never folded
  CHECK_FALSE(gw::tip_folded_before_loss(trace("success", 1.6)));       // only losses are told
  gw::EpisodeTrace no_obs = trace("wrong_branch", 1.6);
  no_obs.observation.clear();
  CHECK_FALSE(gw::tip_folded_before_loss(no_obs));

  // The summary records it for every wrong branch, and the table's failure modes count it.
  const nlohmann::json summary =
      gw::summarize_episodes({trace("wrong_branch", 1.6), trace("wrong_branch", -1), trace("success", 1.6)});
  CHECK(summary["results"][0]["folded"] == true);
  CHECK(summary["results"][1]["folded"] == false);
  CHECK_FALSE(summary["results"][2].contains("folded"));
}

TEST_CASE("the deformed coronary's T3 fold-back: the shipped actor's caught tip folds over, the scripted rule "
          "passes",
          "[runner][policy][fold]") {
  // docs/results.md, "The deformed coronary's T3 folds back": seed 30 is one of the six table episodes where the actor,
  // aimed, turns a caught tip, the tip snaps back and the folded wire goes into the wrong branch.
  const std::string mesh = std::string(GW_SOURCE_DIR) + "/anatomies/test/coronary_deformed/coronary_deformed.stl";
  const gw::NavigationAnatomy nav = gw::load_navigation_anatomy(mesh);  // extracted, as evaluate does
  auto run = [&](const std::string& kind, int target, std::uint64_t seed) {
    auto make = [&] { return gw::make_controller(kind, gw::default_policy_path()); };
    gw::TaskConfig config;
    make()->adapt(config);
    const gw::NavigationTask task = gw::make_navigation_task(config, gw::default_wire_params(), {nav.anatomy});
    return gw::run_batch(task, {{0, target, seed}}, make, 1, {}).front();
  };
  const gw::EpisodeTrace folded = run("policy", 3, 30);
  REQUIRE(folded.outcome == "wrong_branch");
  CHECK(folded.omega_at_loss <= -0.9);  // aimed at the fork's centre, so "aimed" alone would mislead
  CHECK(gw::tip_folded_before_loss(folded));
  CHECK(run("scripted-omega", 3, 30).outcome == "success");
  // An aimed loss without a fold (T1 at D1, seed 0): the wire body goes into the wrong branch.
  const gw::EpisodeTrace aimed = run("policy", 1, 0);
  REQUIRE(aimed.outcome == "wrong_branch");
  CHECK(aimed.omega_at_loss <= -0.9);
  CHECK_FALSE(gw::tip_folded_before_loss(aimed));
}

TEST_CASE("navigation outputs: trajectories, VTK and a biplane PNG per target", "[runner]") {
  const ShortT1 t1(12);
  const auto traces = gw::run_batch(t1.task, gw::plan_episodes(t1.task, 0, "1", 1, 0),
                                    [] { return gw::make_push_only_controller(); }, 1, {});
  const fs::path dir = scratch_dir("outputs");
  const auto files = gw::write_navigation_outputs(dir.string(), t1.nav, traces, {"test"});
  for (const char* name : {"vessel.vtp", "centerline.vtp", "target1_path.vtp", "target1.png", "episode0_target1.json",
                           "episode0_target1.vtp"}) {
    INFO(name);
    CHECK(fs::exists(dir / name));
    CHECK(fs::file_size(dir / name) > 100);
  }
  CHECK(files.size() >= 6);
  std::ifstream png(dir / "target1.png", std::ios::binary);
  char magic[4] = {};
  png.read(magic, 4);
  CHECK(std::string(magic + 1, 3) == "PNG");
  // The ParaView time series: one wire file per recorded shape (frame 0 and the last), the static
  // wall listed at each time, not written again.
  const auto& shapes = traces.front().wire_shape_frame;
  REQUIRE(shapes.size() >= 2);
  CHECK(fs::exists(dir / "episode0_target1.pvd"));
  for (int f : shapes) {
    char name[32];
    std::snprintf(name, sizeof name, "wire_%05d.vtp", f);
    CHECK(fs::exists(dir / "episode0_target1" / name));
  }
  std::ifstream pvd(dir / "episode0_target1.pvd");
  const std::string collection((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  CHECK(collection.find("part=\"1\" file=\"vessel.vtp\"") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "episode0_target1" / "vessel_00000.vtp"));
}

TEST_CASE("navigation outputs of a beating wall: its surface per recorded frame, ED and ES in the figure", "[runner]") {
  const ShortT1 t1(12);
  const auto traces = gw::run_batch(t1.task, gw::plan_episodes(t1.task, 0, "1", 1, 0),
                                    [] { return gw::make_push_only_controller(); }, 1, {});
  // A wall shaken along x: D(t) = A sin(2 pi t) at 60 bpm, so end-systole (phase 1/3) is at t = 1/3 s.
  const gw::VesselScene& rest = *t1.nav.anatomy.scene;
  const Eigen::Vector3d amplitude(1.0, 0.0, 0.0);
  const gw::VesselScene beating =
      gw::attach_wall_motion(rest, gw::rigid_wall_motion(rest.mesh, Eigen::Vector3d::Zero(), amplitude, 60.0));
  REQUIRE(beating.motion);
  CHECK(gw::wall_time_at_phase(beating, 0.0) == 0.0);
  CHECK(gw::wall_time_at_phase(beating, 1.0 / 3.0) == Approx(1.0 / 3.0));
  const double t = 0.1;
  const gw::TriangleMesh moved = gw::wall_mesh_at(beating, t);
  REQUIRE(moved.V.rows() == rest.mesh.V.rows());
  CHECK((moved.V - rest.mesh.V).col(0).maxCoeff() == Approx(std::sin(2 * M_PI * t)).epsilon(1e-12));
  CHECK((moved.V - rest.mesh.V).col(1).cwiseAbs().maxCoeff() == 0.0);
  CHECK(moved.F == rest.mesh.F);

  const fs::path dir = scratch_dir("outputs_beating");
  const auto files = gw::write_navigation_outputs(dir.string(), t1.nav, traces, {"test"}, &beating);
  const auto& shapes = traces.front().wire_shape_frame;
  REQUIRE(shapes.size() >= 2);
  for (int f : shapes) {
    char wire[32];
    std::snprintf(wire, sizeof wire, "wire_%05d.vtp", f);
    CHECK(fs::exists(dir / "episode0_target1" / wire));
  }
  std::ifstream pvd(dir / "episode0_target1.pvd");
  const std::string collection((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  // One wall file per distinct phase: phase 0 (t = 0) and the last frame's.
  CHECK(collection.find("part=\"1\" file=\"wall/phase_000000000.vtp\"") != std::string::npos);
  CHECK(fs::exists(dir / "wall" / "phase_000000000.vtp"));
  const auto walls = std::distance(fs::directory_iterator(dir / "wall"), fs::directory_iterator{});
  CHECK(walls == static_cast<long>(shapes.size()));  // 12 steps of 0.04 s at 60 bpm: every phase differs
  CHECK(gw::wire_shape_stride(&beating, 0.04) == 3);
  CHECK(gw::wire_shape_stride(&rest, 0.04) == 25);
  CHECK(gw::wire_shape_stride(nullptr, 0.04) == 25);
  CHECK(fs::exists(dir / "target1.png"));
  CHECK(std::find(files.begin(), files.end(), (dir / "episode0_target1.pvd").string()) != files.end());
}

TEST_CASE("controllers: the scripted omega rule in both turn directions", "[runner]") {
  gw::Observation obs{};
  const auto cw = gw::make_controller("scripted-omega", "");
  const auto ccw = gw::make_controller("scripted-omega-ccw", "");
  CHECK(cw->name() == "scripted-omega");
  CHECK(ccw->name() == "scripted-omega-ccw");
  for (double omega : {1.0, 0.0, -0.94}) {  // not yet aimed: full rate, each its own way
    obs[gw::obs_index::kOmega] = omega;
    CHECK(cw->act(obs).rotation == 1.0);
    CHECK(ccw->act(obs).rotation == -1.0);
  }
  for (double omega : {-0.95, -1.0}) {  // aimed: both hold
    obs[gw::obs_index::kOmega] = omega;
    CHECK(cw->act(obs).rotation == 0.0);
    CHECK(ccw->act(obs).rotation == 0.0);
  }
  CHECK_THROWS_AS(gw::make_scripted_omega_controller(-0.95, 0.5), std::invalid_argument);
  CHECK_THROWS_WITH(gw::make_controller("scripted-omega-cw", ""), Catch::Contains("scripted-omega-ccw"));
}

TEST_CASE("evaluation table: the paper's rows and a Markdown table that says why rows fall short", "[runner]") {
  const auto rows = gw::paper_table();
  REQUIRE(rows.size() >= 12);  // the paper's 10, then rows beyond it (issues 41, 36)
  CHECK(rows[10].name == "trifurcation tree");
  for (size_t i = 10; i < rows.size(); ++i) CHECK(rows[i].paper_success < 0);  // no paper figure: "—" in the table
  // The junction trees' corrected pair sits beside the frozen ones (issue 41), once each.
  for (const char* name : {"trifurcation tree (outer side branches)", "closely spaced forks (outer side branches)"})
    CHECK(std::count_if(rows.begin(), rows.end(), [&](const gw::EvaluationRow& r) { return r.name == name; }) == 1);
  CHECK(rows[0].episodes == 100);
  CHECK(rows[4].paper_success == Approx(0.62));
  CHECK(rows[1].base_policy);
  CHECK_FALSE(rows[8].base_policy);

  gw::EvaluationOptions o;
  o.index_path = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";
  o.controllers = {"push-only", "policy"};
  o.extract_centerlines = false;
  o.episode_scale = 0.02;  // 2 episodes
  o.reachability_seeds = 0;  // probing is tested below
  gw::EvaluationRow row = rows[0];
  row.anatomies = {"t1_straight_y"};
  gw::EvaluationRow missing = row;
  missing.name = "missing anatomy";
  missing.anatomies = {"no_such_anatomy"};
  const nlohmann::json e = gw::run_evaluation({row, missing}, o);
  REQUIRE(e["rows"].size() == 2);
  CHECK(e["rows"][0]["episodes"] == 2);
  CHECK(e["rows"][0]["results"]["push-only"]["episodes"] == 2);
  CHECK_FALSE(e["rows"][0]["results"].contains("sac-policy"));  // no policy given: column skipped, with a note
  CHECK(e["rows"][0]["notes"].size() == 1);
  CHECK(e["rows"][0]["reachability"].empty());
  CHECK(e["rows"][1]["skipped"].get<std::string>().find("no_such_anatomy") != std::string::npos);
  CHECK(e["settings"]["intermediate_target_mm"] == gw::TaskConfig{}.intermediate_target_mm);
  gw::EvaluationOptions bad = o;
  bad.task.intermediate_target_mm = -1;  // the task refuses it; the row says so instead of the run dying
  const nlohmann::json refused = gw::run_evaluation({row}, bad);
  CHECK(refused["rows"][0]["skipped"].get<std::string>().find("intermediate_target_mm") != std::string::npos);
  const std::string md = gw::evaluation_to_markdown(e);
  CHECK(md.find("| training anatomies | 2 | — |") != std::string::npos);
  CHECK(md.find("| 95% |") != std::string::npos);
  CHECK(md.find("**missing anatomy**: skipped") != std::string::npos);

  // Failure modes name the anatomy, target and the bifurcation where episodes were lost, most frequent first.
  nlohmann::json by_hand = {{"rows", nlohmann::json::array()}};
  nlohmann::json lost = {{"outcome", "wrong_branch"}, {"anatomy", "coronary"}, {"target", 3},
                         {"detail", "entered a wrong branch before goal 2 of 3"}};
  nlohmann::json other = {{"outcome", "wrong_branch"}, {"anatomy", "coronary"}, {"target", 1},
                          {"detail", "entered a wrong branch before goal 1 of 2"}};
  nlohmann::json broke = {{"outcome", "diverged"}, {"anatomy", "coronary"}, {"target", 6},
                          {"detail", "physics diverged: NaN"}};
  nlohmann::json summary = {{"episodes", 4},
                            {"successes", 0},
                            {"success_rate", 0.0},
                            {"outcomes", {{"success", 0}, {"wrong_branch", 3}, {"diverged", 1}}},
                            {"results", {other, lost, lost, broke}}};
  by_hand["rows"].push_back({{"name", "coronary-like"}, {"episodes", 4}, {"paper", 0.94},
                             {"notes", nlohmann::json::array()}, {"results", {{"scripted-omega", summary}}}});
  const std::string why = gw::evaluation_to_markdown(by_hand);
  CHECK(why.find("wrong_branch 3 (coronary T3 goal 2/3 x2, coronary T1 goal 1/2 x1)") != std::string::npos);
  // The mirrored scripted rule has its own column, beside the scripted one; a table run without it shows "—".
  CHECK(why.find("| coronary-like | 4 | — | — | — | 0% | — | 94% |") != std::string::npos);
  nlohmann::json mirrored = by_hand;
  nlohmann::json half = summary;
  half["successes"] = 2;
  half["success_rate"] = 0.5;
  mirrored["rows"][0]["results"]["scripted-omega-ccw"] = half;
  CHECK(gw::evaluation_to_markdown(mirrored).find("| 0% | 50% | 94% |") != std::string::npos);
  // SAC is paired with both directions of the rule on the same episodes.
  mirrored["rows"][0]["results"]["sac-policy"] = summary;  // lost every episode, as scripted-omega did
  for (int k = 0; k < 4; ++k)
    for (const char* column : {"sac-policy", "scripted-omega", "scripted-omega-ccw"})
      mirrored["rows"][0]["results"][column]["results"][k]["seed"] = k;
  auto& won_by_ccw = mirrored["rows"][0]["results"]["scripted-omega-ccw"]["results"];
  won_by_ccw[0]["outcome"] = won_by_ccw[1]["outcome"] = "success";
  CHECK(gw::evaluation_to_markdown(mirrored).find("| won 0, lost 0 (p 1.00); other way: won 0, lost 2 (p 0.50) |") !=
        std::string::npos);
  // With omega at the loss recorded, each place says how many of its losses the controller had aimed.
  nlohmann::json aimed_row = by_hand;
  auto& eps = aimed_row["rows"][0]["results"]["scripted-omega"]["results"];
  eps[1]["omega_at_loss"] = -0.97;  // lost at T3 although bent away from the wrong branch
  eps[2]["omega_at_loss"] = 0.4;    // lost at T3 bent towards it
  eps[0]["omega_at_loss"] = -0.9;   // the threshold counts as aimed
  const std::string aimed = gw::evaluation_to_markdown(aimed_row);
  CHECK(aimed.find("wrong_branch 3 (coronary T3 goal 2/3 x2 aimed 1, coronary T1 goal 1/2 x1 aimed 1)") !=
        std::string::npos);
  CHECK(why.find("diverged 1 (coronary T6 x1)") != std::string::npos);
  CHECK(why.find("| coronary-like | 4 | — | — | — | 0% | — | 94% | — | — |") != std::string::npos);

  // A target no rotation reaches is marked where it was lost, and SAC's rate over the others is shown.
  nlohmann::json win = {{"outcome", "success"}, {"anatomy", "coronary"}, {"target", 1}, {"detail", ""}};
  nlohmann::json win6 = win;
  win6["target"] = 6;
  nlohmann::json sac = summary;
  sac["results"] = {win, lost, lost, win6};
  sac["successes"] = 2;
  sac["success_rate"] = 0.5;
  for (int k = 0; k < 4; ++k) {  // episode k has seed k in both columns, as evaluate runs them
    sac["results"][k]["seed"] = k;
    by_hand["rows"][0]["results"]["scripted-omega"]["results"][k]["seed"] = k;
  }
  by_hand["rows"][0]["results"]["sac-policy"] = sac;
  by_hand["rows"][0]["reachability"] = {{{"key", "coronary T3"}, {"anatomy", "coronary"}, {"target", 3},
                                         {"reachable", false}, {"episodes", 16}}};
  const std::string marked = gw::evaluation_to_markdown(by_hand);
  // SAC's 2 of 4 against the paper's 47 of 50: 44 points below, Fisher p 0.039.
  CHECK(marked.find("| 94% | -44 points (p 0.04) | 100% (2/2) |") != std::string::npos);
  // Same four episodes for both columns (same seed per episode): SAC 2 of 4, scripted 0 of 4.
  CHECK(marked.find("| 50% | 15-85% |") != std::string::npos);
  CHECK(marked.find("| won 2, lost 0 (p 0.50) |") != std::string::npos);
  CHECK(marked.find("coronary T3 goal 2/3 [unreachable] x2") != std::string::npos);
  CHECK(marked.find("coronary T1 goal 1/2 x1") != std::string::npos);

  // Episodes nothing reached from their start are counted where they were lost; the row's ceiling is shown.
  by_hand["rows"][0]["ceiling"] = {{"episodes", 4}, {"reached", 3}, {"reached_by_a_controller", 2},
                                   {"reached_only_by_a_schedule", {{{"anatomy", "coronary"}, {"target", 3},
                                                                    {"seed", 2}, {"schedule", "spin-1"}}}},
                                   {"reached_by_none", {{{"anatomy", "coronary"}, {"target", 3}, {"seed", 1}}}}};
  const std::string ceiling = gw::evaluation_to_markdown(by_hand);
  CHECK(ceiling.find("| won 2, lost 0 (p 0.50) | 75% (3/4) |") != std::string::npos);
  CHECK(ceiling.find("coronary T3 goal 2/3 [unreachable] x2 out-of-reach 1") != std::string::npos);
}

TEST_CASE("evaluate --rows: comma-separated texts pick rows in the table's order, a text matching none is refused",
          "[runner]") {
  const auto table = gw::paper_table();
  CHECK(gw::select_rows(table, "").size() == table.size());
  const auto picked = gw::select_rows(table, "var1,coronary");  // asked out of order: the table's order
  REQUIRE(picked.size() == 5);  // and the beating coronary rows (issue 36)
  CHECK(picked[0].name == "sensitivity: var1");
  CHECK(picked[1].name == "coronary-like");
  CHECK(picked[2].name == "deformed coronary");
  CHECK(picked[3].name == "beating coronary 60 bpm");
  CHECK(picked[4].name == "beating coronary 100 bpm");
  CHECK(gw::select_rows(table, "coronary,deformed").size() == 4);  // a row two texts match is kept once
  CHECK_THROWS_WITH(gw::select_rows(table, "var1,coronery"), Catch::Contains("--rows 'coronery'"));
  CHECK_THROWS_WITH(gw::select_rows(table, ","), Catch::Contains("names no row"));
  // an anatomy index is a row of its own after the table's: every anatomy it lists by its truth, 5 episodes each
  const std::string index = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";
  const auto pool = gw::select_rows(table, "var1," + index);
  REQUIRE(pool.size() == 2);
  CHECK(pool[1].name == "pool " + index);
  CHECK(pool[1].anatomies.size() > 20);
  CHECK(pool[1].episodes == 5 * static_cast<int>(pool[1].anatomies.size()));
  CHECK(pool[1].paper_success < 0);
  CHECK(pool[1].anatomies[0].find(".truth.json") != std::string::npos);
  CHECK_THROWS_WITH(gw::select_rows(table, "/nonexistent/pool.json"), Catch::Contains("/nonexistent/pool.json"));
}

TEST_CASE("evaluate --wire: the rows run with the given wire, recorded in the settings, and a bad file is refused",
          "[runner]") {
  gw::EvaluationOptions o;
  o.index_path = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";
  o.controllers = {"push-only"};
  o.extract_centerlines = false;
  o.episode_scale = 0.02;  // 2 episodes
  o.reachability_seeds = 0;
  const gw::EvaluationRow row{"t1", {"t1_straight_y"}, 100, 0.95, false};
  const nlohmann::json plain = gw::run_evaluation({row}, o);
  CHECK(plain["settings"]["wire"] == "");
  // A straighter tip (0.05 /mm instead of 0.2) pushed the same way from the same starts: other episodes.
  nlohmann::json params = nlohmann::json::parse(std::ifstream(std::string(GW_SOURCE_DIR) + "/engine/wire/coronary_014.json"));
  params["tip_curvature_per_mm"] = 0.05;
  const std::string path = (std::filesystem::temp_directory_path() / "gw_evaluate_wire_test.json").string();
  std::ofstream(path) << params.dump();
  o.wire_path = path;
  const nlohmann::json straighter = gw::run_evaluation({row}, o);
  CHECK(straighter["settings"]["wire"] == path);
  const nlohmann::json& a = plain["rows"][0]["results"]["push-only"]["results"];
  const nlohmann::json& b = straighter["rows"][0]["results"]["push-only"]["results"];
  REQUIRE(a.size() == 2);
  REQUIRE(b.size() == 2);
  CHECK(a != b);
  CHECK(gw::evaluation_to_markdown(straighter).find("Wire parameters from " + path) != std::string::npos);
  CHECK(gw::evaluation_to_markdown(plain).find("Wire parameters") == std::string::npos);
  o.wire_path = path + ".missing";
  CHECK_THROWS_WITH(gw::run_evaluation({row}, o), Catch::Contains(".missing"));
  std::filesystem::remove(path);
}

TEST_CASE("the table's ceiling: episodes no controller reached are re-run from the same start with the rotation "
          "schedules",
          "[runner]") {
  gw::EvaluationOptions o;
  o.index_path = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";
  o.controllers = {"push-only"};  // reaches a target about half the time: leaves episodes to probe
  o.extract_centerlines = false;
  o.episode_scale = 0.06;  // 6 episodes
  o.reachability_seeds = 1;
  o.threads = 2;
  const gw::EvaluationRow row{"t1", {"t1_straight_y"}, 100, 0.95, false};
  const nlohmann::json e = gw::run_evaluation({row}, o);
  const nlohmann::json& r = e["rows"][0];
  REQUIRE(r.contains("ceiling"));
  const nlohmann::json& c = r["ceiling"];
  const int push = r["results"]["push-only"]["successes"];
  CHECK(c["episodes"] == 6);
  CHECK(c["reached_by_a_controller"] == push);
  CHECK(c["reached"].get<int>() ==
        push + static_cast<int>(c["reached_only_by_a_schedule"].size()));
  CHECK(c["reached"].get<int>() + static_cast<int>(c["reached_by_none"].size()) == 6);
  // t1's targets are reached by the scripted rule from every start (results table): push-only's losses are
  // the controller's, and a schedule finds each of them.
  INFO("push-only " << push << "/6");
  REQUIRE(push < 6);
  CHECK(c["reached"] == 6);
  // Each is the schedule's own episode: re-run alone from that seed, it reaches the target.
  const std::vector<gw::Anatomy> anatomies = gw::load_row_anatomies(row, o);
  const gw::NavigationTask task = gw::make_navigation_task(gw::TaskConfig{}, gw::default_wire_params(), anatomies);
  for (const nlohmann::json& ep : c["reached_only_by_a_schedule"]) {
    auto schedule = gw::make_rotation_schedule(ep["schedule"].get<std::string>());
    CHECK(gw::run_episode(task, 0, ep["target"].get<int>(), ep["seed"].get<std::uint64_t>(), *schedule, {}).outcome ==
          "success");
  }
}

TEST_CASE("success statistics: Wilson intervals and the paired sign test", "[runner]") {
  // Reference values from the closed form (Wilson 1927), computed independently.
  const gw::RateInterval ci = gw::wilson_interval(44, 50);
  CHECK(ci.low == Approx(0.7620).margin(1e-4));
  CHECK(ci.high == Approx(0.9438).margin(1e-4));
  CHECK(gw::wilson_interval(50, 50).high == Approx(1.0));
  CHECK(gw::wilson_interval(50, 50).low == Approx(0.9287).margin(1e-4));  // not degenerate at n of n
  CHECK(gw::wilson_interval(0, 50).low == Approx(0.0).margin(1e-12));
  CHECK(gw::wilson_interval(0, 0).high == 1.0);
  CHECK_THROWS_WITH(gw::wilson_interval(5, 4), Catch::Contains("5 successes of 4 episodes"));
  // Exact binomial: 2 vs 4 discordant pairs -> 2 (1 + 6 + 15) / 64; 0 vs 5 -> 2 / 32.
  CHECK(gw::sign_test_p(2, 4) == Approx(0.6875));
  CHECK(gw::sign_test_p(4, 2) == Approx(0.6875));
  CHECK(gw::sign_test_p(0, 5) == Approx(0.0625));
  CHECK(gw::sign_test_p(0, 0) == 1.0);
  // Fisher's exact test, against R's fisher.test: the tea-tasting table and a lopsided one.
  CHECK(gw::fisher_exact_p(3, 4, 1, 4) == Approx(0.485714).margin(1e-6));
  CHECK(gw::fisher_exact_p(1, 10, 11, 14) == Approx(0.002759).margin(1e-6));
  CHECK(gw::fisher_exact_p(11, 14, 1, 10) == Approx(0.002759).margin(1e-6));  // symmetric in the two rows
  CHECK(gw::fisher_exact_p(42, 50, 47, 50) == Approx(0.199717).margin(1e-6));  // our coronary against the paper's
  CHECK(gw::fisher_exact_p(50, 50, 50, 50) == Approx(1.0));
  CHECK_THROWS_WITH(gw::fisher_exact_p(51, 50, 47, 50), Catch::Contains("51 successes of 50 episodes"));
  CHECK(gw::sign_test_p(3, 3) == 1.0);
  CHECK(gw::sign_test_p(0, 1000) < 1e-250);

  // Pairing is by (anatomy, target, seed); an episode only one side ran is ignored.
  auto ep = [](int seed, bool ok) {
    return nlohmann::json{{"anatomy", "var1"}, {"target", 2}, {"seed", seed}, {"outcome", ok ? "success" : "wrong_branch"}};
  };
  const nlohmann::json a = {{"results", {ep(0, true), ep(1, true), ep(2, false), ep(3, true), ep(9, true)}}};
  const nlohmann::json b = {{"results", {ep(0, true), ep(1, false), ep(2, true), ep(3, false)}}};
  const gw::PairedComparison c = gw::compare_paired(a, b);
  CHECK(c.paired == 4);
  CHECK(c.only_first == 2);
  CHECK(c.only_second == 1);
  CHECK(c.sign_test_p == Approx(1.0));
}

TEST_CASE("rotation schedules: the family, their rules, unknown names", "[runner]") {
  CHECK(gw::rotation_schedule_names().size() == 8);
  gw::Observation obs{};
  obs[gw::obs_index::kOmega] = 0.5;  // tip bent towards the wrong branch
  CHECK(gw::make_rotation_schedule("aim-0.95")->act(obs).rotation == 1.0);
  CHECK(gw::make_rotation_schedule("aim-0.95-ccw")->act(obs).rotation == -1.0);
  obs[gw::obs_index::kOmega] = -0.8;
  CHECK(gw::make_rotation_schedule("aim-0.95")->act(obs).rotation == 1.0);
  CHECK(gw::make_rotation_schedule("aim-0.7")->act(obs).rotation == 0.0);  // aimed well enough: hold
  CHECK(gw::make_rotation_schedule("spin-0.3")->act(obs).rotation == -0.3);
  auto wiggle = gw::make_rotation_schedule("wiggle");
  CHECK(wiggle->act(obs).rotation == 0.0);
  CHECK(wiggle->act(obs).rotation == Approx(std::sin(0.3)));
  CHECK(gw::make_rotation_schedule("wiggle")->act(obs).rotation == 0.0);  // a fresh one starts again
  CHECK_THROWS_WITH(gw::make_rotation_schedule("spin+2"), Catch::Contains("known: aim-0.95"));
}

TEST_CASE("reachability: a reachable target stops at the first success, a cut-short one tries the whole family",
          "[runner]") {
  const ShortT1 full(0);  // automatic step limit: targets can be reached
  const auto reached = gw::probe_reachability(full.task, {{0, 1}}, 2, 1);
  REQUIRE(reached.size() == 1);
  CHECK(reached[0].reachable);
  CHECK(reached[0].error.empty());
  CHECK(reached[0].episodes < 16);
  CHECK(gw::to_json(reached[0])["reached_by"]["schedule"] == reached[0].schedule);

  const ShortT1 cut(10);  // 10 steps = 4 mm: no schedule can get there
  const auto none = gw::probe_reachability(cut.task, {{0, 1}, {0, 2}}, 1, 2);
  REQUIRE(none.size() == 2);
  for (const auto& r : none) {
    CHECK_FALSE(r.reachable);
    CHECK(r.episodes == 8);
    CHECK_FALSE(gw::to_json(r).contains("reached_by"));
  }
  const auto bad = gw::probe_reachability(cut.task, {{0, 9}}, 1, 1);
  CHECK_FALSE(bad[0].reachable);
  CHECK(bad[0].error.find("target 9") != std::string::npos);
}

TEST_CASE("a tip that whips free after winding up against the wall stays in the vessel", "[runner][whip]") {
  // t4's back-curving exit, target 1, the scripted omega controller spinning the wire while the tip is
  // held by the wall: torsion builds up and the tip snaps round at metres per second. With one 0.5 ms
  // linearisation per sub-step the tip left the vessel in 3 of these 4 episodes ("wire point ... outside
  // the vessel wall", t ~ 7.45 s); step() now halves sub-steps while the wire moves that fast.
  const std::string t4 = std::string(GW_SOURCE_DIR) + "/anatomies/train/t4_s_curving_back/t4_s_curving_back";
  const gw::NavigationAnatomy nav =
      gw::load_navigation_anatomy(t4 + ".stl", {1.0, std::nullopt, t4 + ".truth.json", false});
  const gw::NavigationTask task = gw::make_navigation_task(gw::TaskConfig{}, gw::default_wire_params(), {nav.anatomy});
  const auto requests = gw::plan_episodes(task, 0, "1", 4, 3);
  const auto traces = gw::run_batch(task, requests, [] { return gw::make_scripted_omega_controller(); }, 2, {});
  REQUIRE(traces.size() == 4);
  for (const auto& t : traces) {
    INFO("seed " << t.seed << ": " << t.outcome << " " << t.detail);
    CHECK(t.outcome != "diverged");
    CHECK(t.detail.find("outside the vessel wall") == std::string::npos);
  }
}

TEST_CASE("a pool's row keeps each entry's wire and heart rate", "[runner][pool]") {
  const std::string stem = std::string(GW_SOURCE_DIR) + "/anatomies/test/coronary/coronary";  // field at phase 0
  const fs::path d = scratch_dir("pool_row_entries");
  std::ofstream(d / "index.json") << R"({"anatomies": [{"name": "beats", "mesh": ")" << stem << R"(.stl", "truth": ")"
                                  << stem << R"(.truth.json", "heart_rate_bpm": 90, "wire": ")" << GW_SOURCE_DIR
                                  << R"(/engine/wire/aortic_035_angled.json"}]})";
  gw::EvaluationRow row = gw::index_row((d / "index.json").string());
  gw::EvaluationOptions o;
  o.extract_centerlines = false;
  std::vector<gw::Anatomy> a = gw::load_row_anatomies(row, o);
  REQUIRE(a.size() == 1);
  REQUIRE(a[0].wire);
  CHECK(a[0].wire->diameter_mm == 0.889);
  REQUIRE(a[0].scene->motion);
  CHECK(a[0].scene->motion->heart_rate_bpm == 90.0);
  row.heart_rate_bpm = 60;  // a beating row's rate is the row's
  a = gw::load_row_anatomies(row, o);
  CHECK(a[0].scene->motion->heart_rate_bpm == 60.0);
}
