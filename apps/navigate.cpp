// navigate: steer a guidewire to a numbered target of a vessel surface, zero-shot, with the
// shipped SAC policy (or a baseline controller).
//   navigate --anatomy coronary.stl --target 3
//   navigate --anatomy coronary.stl --target all --episodes 10 --seed 1 --json --out runs/coronary
// Pipeline: load + repair mesh (intake_surface: every repair on stderr and in --json) -> centerline (CGAL MCF, cached) -> plan path -> episodes in which
// the policy turns the wire within 20 mm of each bifurcation and the wire is only pushed elsewhere.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>
#include <unistd.h>

#include "lib/runner/controller.hpp"
#include "lib/runner/rotation_schedules.hpp"
#include "lib/runner/episode_batch.hpp"
#include "lib/runner/heart_motion.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "lib/runner/navigation_outputs.hpp"
#include "lib/runner/procedure_options.hpp"
#include "lib/runner/replay_controller.hpp"
#include "plan/plan_json.hpp"
#include "base/util/parse_point.hpp"
#include "base/util/read_json_file.hpp"
#include "lib/runner/task_options.hpp"
#include "centerline/target_table.hpp"
#include "base/graph/nearest_target.hpp"
#include "task/navigation_task.hpp"
#include "task/task_config_json.hpp"
#include "engine/wire/wire_params.hpp"

namespace {

// What the command line asks for.
struct NavigateArgs {
  std::string anatomy_path, target = "all", policy = gw::default_policy_path(), controller_kind = "policy";
  std::string inlet_text, out_dir, wire_path, target_point_text, replay_path;
  gw::NavigationAnatomyOptions load;
  int episodes = 1, threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::uint64_t seed = 0;
  bool print_json = false, list = false, no_cache = false, scale_given = false;
  gw::TaskOptions task;
  gw::ProcedureOptions procedure;  // --reshape-tip, --reshape-tip-length, --step-time-limit
  gw::HeartSettings heart;
};

void add_navigate_options(CLI::App& app, NavigateArgs& a) {
  app.add_option("--anatomy,anatomy", a.anatomy_path, "vessel surface (.stl, .obj, .ply), millimetres")->required();
  auto* target_option = app.add_option("--target", a.target, "target number, 'all' or 'random' (see --list)");
  app.add_option("--target-point", a.target_point_text,
                 "x,y,z: the target whose end is nearest this point (mm, RAS, e.g. a 3D Slicer fiducial)")
      ->excludes(target_option);
  app.add_option("--episodes", a.episodes, "episodes per target ('random': in total)");
  app.add_option("--seed", a.seed, "episode k uses seed S+k: same seed, same episode");
  app.add_option("--policy", a.policy, "actor JSON (default: the shipped policy/trained/sac_actor.json)");
  app.add_option("--controller", a.controller_kind,
                 "policy | push-only | scripted-omega | scripted-omega-ccw (baselines) | a rotation schedule: " +
                     gw::rotation_schedule_list());
  app.add_option("--inlet", a.inlet_text, "x,y,z near the insertion point (default: the widest vessel end)");
  app.add_option("--scale", a.load.scale, "multiply coordinates (1000 for metres -> mm); default: automatic, a surface "
                                         "under 2 units across is read as metres");
  app.add_option("--centerline", a.load.centerline_path,
                 "use this centerline file (.json, VMTK .vtp, 3D Slicer .mrk.json) instead of extracting one");
  app.add_option("--wire", a.wire_path, "guidewire parameter JSON (default: 0.014\" coronary wire)");
  app.add_option("--replay", a.replay_path,
                 "replay a procedure plan (`plan --out DIR` writes DIR/plan.json): its task, target, seed, wire, heart "
                 "and inlet, its actions; the same trajectory bit for bit")
      ->excludes(target_option);
  gw::add_task_options(app, a.task);
  gw::add_procedure_options(app, a.procedure);
  app.add_option("--heart-rate", a.heart.heart_rate_bpm,
                 "the vessel beats at this rate, bpm (0 = static; docs/beating_heart.md): its wall and centerline "
                 "follow --motion, else the anatomy's own field (STEM.motion.json or the spec's deformation beside the mesh)")
      ->check(CLI::Range(0.0, 300.0));
  app.add_option("--motion", a.heart.motion_path, "cardiac motion JSON (engine/scene/wall_motion.hpp; docs/beating_heart.md)");
  app.add_option("--threads", a.threads, "episodes run in parallel");
  app.add_option("--out", a.out_dir, "write trajectories (JSON, VTK .vtp) and biplane PNGs here");
  app.add_flag("--json", a.print_json, "print one JSON summary on stdout");
  app.add_flag("--list", a.list, "print the targets (id, position, path length, bifurcations) and exit");
  app.add_flag("--no-cache", a.no_cache, "recompute the centerline even when cached");
}

// The intake's repairs and warnings, and what a wide inlet means for the wire and the task, on stderr.
void report_anatomy(const NavigateArgs& a, const gw::NavigationAnatomy& nav, const gw::TaskConfig& config) {
  for (const std::string& r : nav.repairs) std::cerr << "repaired: " << a.anatomy_path << ": " << r << "\n";
  for (const std::string& w : nav.mesh_warnings) std::cerr << "warning: " << a.anatomy_path << ": " << w << "\n";
  if (!nav.inlet_warning.empty()) std::cerr << "warning: " << a.anatomy_path << ": " << nav.inlet_warning << "\n";
  if (!nav.inlet_note.empty()) std::cerr << "note: " << a.anatomy_path << ": " << nav.inlet_note << "\n";
  // The default wire is a 0.014" coronary wire made for vessels of about 0.8-2 mm radius; in an
  // aorta (radius 10-15 mm) its tip cannot span the lumen to aim at a branch.
  const double inlet_radius = nav.anatomy.graph.inlet.radius;
  if (a.wire_path.empty() && inlet_radius > config.wide_vessel_radius_mm)
    std::cerr << "note: " << a.anatomy_path << ": the inlet is " << inlet_radius
              << " mm in radius, far above the default 0.014\" coronary wire's range (about 0.8-2 mm); for an aorta "
                 "try --wire "
              << gw::shipped_path("engine/wire/aortic_035_angled.json") << " (0.035\" angled-tip wire)\n";
  if (config.task_scale == gw::TaskScale::kAuto && inlet_radius > config.wide_vessel_radius_mm)
    std::cerr << "note: " << a.anatomy_path << ": wide inlet, so a wrong branch counts once the tip is inside it past its "
                 "ostium and the policy acts within 20 mm of the parent's wall (--task-scale vessel; fixed = the "
                 "paper's millimetres; docs/vessel_scale.md)\n";
}

// The run's JSON summary: the episodes' (summarize_episodes) and what they ran with.
nlohmann::json navigation_summary(const NavigateArgs& a, const gw::NavigationAnatomy& nav, const gw::NavigationTask& task,
                                  const gw::Anatomy& anatomy, const std::string& motion_source,
                                  const std::vector<gw::EpisodeTrace>& traces) {
  const gw::TaskConfig& config = task.config;
  nlohmann::json summary = gw::summarize_episodes(traces);
  summary["anatomy"] = a.anatomy_path;
  summary["controller"] = a.controller_kind == "policy" ? "sac-policy" : a.controller_kind;
  if (a.controller_kind == "policy") summary["policy"] = gw::recorded_path(a.policy);
  if (!a.replay_path.empty()) summary["replay"] = gw::recorded_path(a.replay_path);
  const Eigen::Vector3d& inlet = nav.anatomy.graph.inlet.position;
  summary["inlet"] = {{"source", nav.inlet_source}, {"position", {inlet.x(), inlet.y(), inlet.z()}}};
  if (!nav.inlet_warning.empty()) summary["inlet"]["warning"] = nav.inlet_warning;
  if (!nav.inlet_note.empty()) summary["inlet"]["note"] = nav.inlet_note;
  summary["centerline"] = {{"source", nav.centerline_source},
                           {"seconds", nav.centerline_seconds},
                           {"targets", nav.anatomy.graph.targets.size()},
                           {"bifurcations", nav.anatomy.graph.bifurcations.size()}};
  if (!nav.intake_report.empty()) summary["intake"] = nlohmann::json::parse(nav.intake_report);
  summary["task"] = gw::task_config_to_json(config);
  summary["intermediate_target_mm"] = config.intermediate_target_mm;
  summary["push_mm_per_s"] = config.push_mm_per_s;
  summary["task_scale"] = task.courses.at(0).at(0).vessel_scale ? "vessel" : "fixed";  // --task-scale, resolved
  if (config.recovery_attempts > 0) summary["recovery_attempts"] = config.recovery_attempts;
  if (config.recovery_assist) summary["recovery_assist"] = true;
  if (a.procedure.reshape_tip_per_mm > 0) summary["reshape_tip_per_mm"] = a.procedure.reshape_tip_per_mm;
  if (a.procedure.reshape_tip_per_mm > 0 && a.procedure.reshape_tip_length_mm > 0)
    summary["reshape_tip_length_mm"] = a.procedure.reshape_tip_length_mm;
  if (a.procedure.step_time_limit_s > 0) summary["step_time_limit_s"] = a.procedure.step_time_limit_s;
  if (config.action != gw::ActionLayout::kRotation) summary["action_layout"] = gw::action_layout_name(config.action);
  if (!motion_source.empty())
    summary["heart"] = {{"heart_rate_bpm", anatomy.scene->motion ? anatomy.scene->motion->heart_rate_bpm : 0.0},
                        {"motion", motion_source}};
  return summary;
}

// The text report: a line per episode, then the strict count and, with recovery (and reshape), the procedures'.
void print_report(const NavigateArgs& a, const gw::NavigationAnatomy& nav, const std::vector<gw::EpisodeTrace>& traces,
                  const nlohmann::json& summary, double wall) {
  std::cout << a.anatomy_path << ": " << nav.anatomy.graph.targets.size() << " targets, "
            << nav.anatomy.graph.bifurcations.size() << " bifurcations (centerline " << nav.centerline_source << ", "
            << nav.centerline_seconds << " s)\n";
  for (std::size_t k = 0; k < traces.size(); ++k) {
    const gw::EpisodeTrace& t = traces[k];
    std::cout << "episode " << k << ": target " << t.target_id << ", seed " << t.seed << " -> " << t.outcome;
    if (!t.detail.empty()) std::cout << " (" << t.detail << ")";
    const int end = gw::strict_end(t);
    std::cout << ", " << end << " steps, " << t.time_s[static_cast<std::size_t>(end)] << " s simulated";
    if (t.recovery_attempts_allowed > 0)
      std::cout << "; with recovery -> " << t.recovery_outcome << " after " << t.recovery_attempts_used
                << " pull-back(s), " << t.time_s.back() << " s simulated";
    if (!t.reshaped.empty()) {
      const nlohmann::json& r = summary["results"][k]["reshape"];
      std::cout << "; tip reshaped to " << t.reshape_tip_per_mm << "/mm over " << t.reshape_tip_length_mm << " mm -> "
                << r["outcome"].get<std::string>() << ", " << r["procedure_time_s"].get<double>()
                << " s simulated in all";
    }
    std::cout << "\n";
  }
  std::cout << summary["successes"].get<int>() << "/" << traces.size() << " reached the target ("
            << 100.0 * summary["success_rate"].get<double>() << "%" << (summary.contains("recovery") ? ", strict" : "")
            << ")";
  for (const char* stage : {"recovery", "reshape"})
    if (summary.contains(stage))
      std::cout << "; with " << stage << " " << summary[stage]["successes"].get<int>() << "/" << traces.size() << " ("
                << 100.0 * summary[stage]["success_rate"].get<double>() << "%)";
  std::cout << " in " << wall << " s\n";
  if (!a.out_dir.empty()) std::cout << "wrote " << summary["files"].size() << " files to " << a.out_dir << "\n";
}

// --replay: the plan's actions, and its task, target, seed, wire, heart and inlet in `a` and `config` (a task
// flag, --controller or --policy beside it is refused: the plan fixes them).
std::vector<gw::Action> take_replay(NavigateArgs& a, gw::TaskConfig& config, const CLI::App& app) {
  if (!a.task.task.empty() || !a.task.flags.empty() || app.count("--controller") || app.count("--policy"))
    throw std::invalid_argument("--replay: the plan fixes the task and the actions; drop --task, the task flags, "
                                "--controller and --policy");
  const nlohmann::json plan = gw::read_json_file(a.replay_path, "plan");
  std::vector<gw::Action> actions = gw::plan_actions_from_json(plan, a.replay_path);
  try {
    config = gw::task_config_from_json(plan.at("task"), gw::TaskConfig{});
    a.target = std::to_string(plan.at("target").get<int>());
    a.seed = plan.at("seed").get<std::uint64_t>();
    const std::string wire = plan.at("wire").get<std::string>();
    if (a.wire_path.empty() && !wire.empty()) a.wire_path = std::filesystem::exists(wire) ? wire : gw::shipped_path(wire);
    if (!app.count("--heart-rate")) a.heart.heart_rate_bpm = plan.at("heart_rate_bpm").get<double>();
    if (a.heart.motion_path.empty()) a.heart.motion_path = plan.at("motion").get<std::string>();
    if (a.inlet_text.empty() && plan.at("inlet").is_array())
      a.load.inlet = Eigen::Vector3d(plan["inlet"][0].get<double>(), plan["inlet"][1].get<double>(), plan["inlet"][2].get<double>());
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(a.replay_path + ": a plan field is missing or of the wrong type (" + e.what() + ")");
  }
  a.episodes = 1;
  a.controller_kind = "replay";
  return actions;
}

// The episodes asked for: the anatomy loaded (or its target list printed), the task made, the batch run, reported.
int navigate(NavigateArgs a, const CLI::App& app) {
  if (a.scale_given && (!(a.load.scale > 0) || !std::isfinite(a.load.scale)))
    throw std::invalid_argument("--scale must be a positive number");
  const auto start = std::chrono::steady_clock::now();
  gw::TaskConfig config = gw::resolve_task_config(a.task);  // a bad --task fails before the mesh loads
  std::vector<gw::Action> replay;
  if (!a.replay_path.empty()) replay = take_replay(a, config, app);
  if (!a.inlet_text.empty()) a.load.inlet = gw::parse_point(a.inlet_text, "--inlet");
  a.load.use_cache = !a.no_cache;
  const gw::NavigationAnatomy nav = gw::load_navigation_anatomy(a.anatomy_path, a.load);
  report_anatomy(a, nav, config);
  if (!a.target_point_text.empty()) {
    a.target = std::to_string(gw::nearest_target(nav.anatomy.graph, gw::parse_point(a.target_point_text, "--target-point")));
    std::cerr << "target: " << a.anatomy_path << ": --target-point is nearest target " << a.target << "\n";
  }
  if (a.list) {
    std::cout << gw::format_target_table(nav.anatomy.graph);
    return 0;
  }
  // Fail on the policy before the simulation starts: a missing or mismatched file is a user error.
  auto make_controller = [&]() -> std::unique_ptr<gw::Controller> {
    if (!a.replay_path.empty()) return gw::make_replay_controller(replay);
    return gw::make_controller(a.controller_kind, a.policy);
  };
  make_controller()->adapt(config);  // the actor's observation and action layouts (an obs/1 actor: the paper's omega)
  const gw::WireParams wire = a.wire_path.empty() ? gw::default_wire_params() : gw::load_wire_params(a.wire_path);
  gw::Anatomy anatomy = nav.anatomy;
  const std::string motion_source = gw::apply_heart_settings(anatomy, a.heart);  // "" = a static wall
  const gw::NavigationTask task = gw::make_navigation_task(config, wire, {anatomy});
  std::vector<gw::EpisodeRequest> requests;
  try {
    requests = gw::plan_episodes(task, 0, a.target, a.episodes, a.seed);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(a.anatomy_path + ": " + e.what());
  }
  const bool show_progress = requests.size() > 1 && isatty(STDERR_FILENO);
  auto progress = [&](int done, int total) {
    if (show_progress) std::fprintf(stderr, "\r[navigate] episode %d/%d", done, total);
  };
  gw::TraceOptions trace;
  trace.step_time_limit_s = a.procedure.step_time_limit_s;
  std::optional<gw::NavigationTask> reshaped;
  if (a.procedure.reshape_tip_per_mm > 0) {
    reshaped = gw::make_reshaped_task(task, a.procedure.reshape_tip_per_mm, a.procedure.reshape_tip_length_mm);
    trace.reshaped = &*reshaped;
  }
  trace.wire_shape_every = a.out_dir.empty() ? 0 : gw::wire_shape_stride(anatomy.scene.get(), config.dt_s * config.frame_skip);
  const std::vector<gw::EpisodeTrace> traces = gw::run_batch(task, requests, make_controller, a.threads, trace, progress);
  if (show_progress) std::fprintf(stderr, "\n");

  nlohmann::json summary = navigation_summary(a, nav, task, anatomy, motion_source, traces);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary["wall_time_s"] = wall;
  if (!a.out_dir.empty()) {
    // The PNG's own summary line names anatomy, target, controller and (for one episode) the seed; this
    // line adds what it cannot: the actor file and, for batches, where the seeds start.
    std::string line = a.controller_kind == "policy" ? "policy " + std::filesystem::path(a.policy).filename().string()
                                                     : summary["controller"].get<std::string>();
    if (requests.size() > 1) line += " | seeds from " + std::to_string(a.seed);
    summary["files"] = gw::write_navigation_outputs(a.out_dir, nav, traces, {line}, anatomy.scene.get());
  }
  if (a.print_json)
    std::cout << summary.dump() << "\n";
  else
    print_report(a, nav, traces, summary, wall);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Navigate a guidewire to a numbered target of a vessel surface with the shipped policy"};
  NavigateArgs args;
  add_navigate_options(app, args);
  CLI11_PARSE(app, argc, argv);
  args.scale_given = app.count("--scale") > 0;
  try {
    return navigate(args, app);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
