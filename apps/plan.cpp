// plan: for one target of a vessel surface, search the simulator for a procedure (push, pull, rotate) that
// reaches it within a tip-force budget, or show what was tried and where the tip got nearest (docs/planning.md).
//   plan --anatomy coronary.stl --target 3 --out runs/plan3
//   navigate --anatomy coronary.stl --replay runs/plan3/plan.json      # the same trajectory, bit for bit
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "base/util/parse_point.hpp"
#include "engine/wire/wire_params.hpp"
#include "lib/runner/controller.hpp"
#include "lib/runner/controller_guides.hpp"
#include "lib/runner/heart_motion.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "lib/runner/navigation_outputs.hpp"
#include "lib/runner/replay_controller.hpp"
#include "lib/runner/run_episode.hpp"
#include "plan/plan_json.hpp"
#include "plan/plan_procedure.hpp"
#include "plan/planning_task.hpp"
#include "task/task_config_json.hpp"

namespace {

struct PlanArgs {
  std::string anatomy_path, inlet_text, out_dir, wire_path, demos_path, lead_in_path;
  int target = 0;
  std::uint64_t seed = 0;
  gw::NavigationAnatomyOptions load;
  gw::HeartSettings heart;
  gw::PlanOptions plan;
  bool print_json = false;
};

void add_plan_options(CLI::App& app, PlanArgs& a) {
  app.add_option("--anatomy,anatomy", a.anatomy_path, "vessel surface (.stl, .obj, .ply), millimetres")->required();
  app.add_option("--target", a.target, "target number (navigate --list shows them)")->required()->check(CLI::PositiveNumber);
  app.add_option("--seed", a.seed, "the episode's seed (its start orientation), as navigate's");
  app.add_option("--wire", a.wire_path, "guidewire parameter JSON (default: 0.014\" coronary wire)");
  app.add_option("--heart-rate", a.heart.heart_rate_bpm, "the vessel beats at this rate, bpm (0 = static), as navigate's")
      ->check(CLI::Range(0.0, 300.0));
  app.add_option("--motion", a.heart.motion_path, "cardiac motion JSON, as navigate's");
  app.add_option("--inlet", a.inlet_text, "x,y,z near the insertion point (default: as navigate's)");
  app.add_option("--centerline", a.load.centerline_path, "use this centerline file instead of extracting one");
  app.add_option("--force-limit", a.plan.force_limit_N, "the budget: no step's tip force above this, N")
      ->check(CLI::PositiveNumber);
  app.add_option("--budget", a.plan.max_env_steps, "env steps the search may simulate over all its branches")
      ->check(CLI::PositiveNumber);
  app.add_option("--hold", a.plan.hold_steps, "env steps one maneuver holds its action")->check(CLI::Range(1, 100));
  app.add_flag("--strict-only", a.plan.strict_only, "search only strict plans (no wrong branch ever entered)");
  app.add_option("--lead-in", a.lead_in_path,
                 "an actor JSON: search from where its episode stopped getting deeper, 1 s before its deepest step "
                 "(the plan's first steps are its own; --demos writes only the search's)");
  app.add_option("--out", a.out_dir, "write plan.json and the replayed episode's PNG, VTK and JSON here");
  app.add_option("--demos", a.demos_path,
                 "write the plan's (observation, action) pairs here, JSON lines, in the plan task's layout (obs/8, act/2)");
  app.add_flag("--json", a.print_json, "print the plan JSON on stdout");
}

// The plan's JSON with what it ran on: navigate --replay reads these back.
nlohmann::json plan_document(const PlanArgs& a, const gw::ProcedurePlan& plan, const gw::TaskConfig& config) {
  nlohmann::json j = gw::plan_to_json(plan);
  j["anatomy"] = gw::recorded_path(a.anatomy_path);
  j["target"] = a.target;
  j["seed"] = a.seed;
  j["task"] = gw::task_config_to_json(config);
  j["wire"] = a.wire_path.empty() ? "" : gw::recorded_path(a.wire_path);
  j["heart_rate_bpm"] = a.heart.heart_rate_bpm;
  j["motion"] = a.heart.motion_path.empty() ? "" : gw::recorded_path(a.heart.motion_path);
  j["inlet"] = a.load.inlet ? nlohmann::json{a.load.inlet->x(), a.load.inlet->y(), a.load.inlet->z()} : nlohmann::json();
  j["force_limit_N"] = a.plan.force_limit_N;
  return j;
}

// The plan replayed as navigate --replay would: its trace (outputs, demonstrations), checked against the plan.
gw::EpisodeTrace replay_plan(const gw::NavigationTask& task, const PlanArgs& a, const gw::ProcedurePlan& plan,
                             const nlohmann::json& doc) {
  auto replay = gw::make_replay_controller(gw::plan_actions_from_json(doc, "plan"));
  gw::TraceOptions options;
  options.wire_shape_every = gw::wire_shape_stride(task.anatomies[0].scene.get(), task.config.dt_s * task.config.frame_skip);
  gw::EpisodeTrace trace = gw::run_episode(task, 0, a.target, a.seed, *replay, options);
  const bool reached = gw::procedure_outcome(trace) == "success";
  if (reached != (plan.kind != gw::PlanKind::kNone) || (reached && trace.time_s.size() != plan.actions.size() + 1))
    throw std::logic_error("the replayed plan did not retrace the search (" + gw::procedure_outcome(trace) +
                           "): the simulation is not deterministic here");
  return trace;
}

// One JSON line per step in control after the lead-in's (`skip` env steps): the observation the plan's step was
// taken from and its [rotation, insertion].
void write_demonstrations(const std::string& path, const gw::EpisodeTrace& trace, const nlohmann::json& doc,
                          std::size_t skip) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  const nlohmann::json& actions = doc["actions"];
  std::size_t next = 0;
  for (std::size_t frame = 0; frame + 1 < trace.time_s.size() && next < actions.size(); ++frame)
    if (trace.agent_in_control[frame + 1]) {
      if (frame >= skip) out << nlohmann::json{{"obs", trace.observation[frame]}, {"action", actions[next]}}.dump() << "\n";
      ++next;
    }
  if (!out) throw std::runtime_error(path + ": write failed");
}

int plan_main(PlanArgs a) {
  if (!a.inlet_text.empty()) a.load.inlet = gw::parse_point(a.inlet_text, "--inlet");
  const gw::NavigationAnatomy nav = gw::load_navigation_anatomy(a.anatomy_path, a.load);
  for (const std::string& r : nav.repairs) std::cerr << "repaired: " << a.anatomy_path << ": " << r << "\n";
  const gw::TaskConfig config = gw::planning_task_config(gw::TaskConfig{});
  const gw::WireParams wire = a.wire_path.empty() ? gw::default_wire_params() : gw::load_wire_params(a.wire_path);
  gw::Anatomy anatomy = nav.anatomy;
  gw::apply_heart_settings(anatomy, a.heart);
  const gw::NavigationTask task = gw::make_navigation_task(config, wire, {anatomy});
  a.plan.guides = gw::controller_guides(gw::default_policy_path());
  if (!a.lead_in_path.empty()) a.plan.lead_in = gw::actor_guide(a.lead_in_path);
  const gw::ProcedurePlan plan = gw::plan_procedure(task, 0, a.target, a.seed, a.plan);
  nlohmann::json doc = plan_document(a, plan, config);
  const gw::EpisodeTrace trace = replay_plan(task, a, plan, doc);
  if (!a.out_dir.empty()) {
    std::filesystem::create_directories(a.out_dir);
    const std::string plan_path = (std::filesystem::path(a.out_dir) / "plan.json").string();
    std::ofstream(plan_path) << doc.dump(1) << "\n";
    gw::write_navigation_outputs(a.out_dir, nav, {trace},
                                 {"plan: " + std::string(gw::plan_kind_name(plan.kind)) + ", target " + std::to_string(a.target)},
                                 anatomy.scene.get());
  }
  if (!a.demos_path.empty())
    write_demonstrations(a.demos_path, trace, doc, plan.lead_in ? static_cast<std::size_t>(plan.lead_in->steps) : 0);
  const gw::SearchStats& last = plan.procedure.maneuvers > 0 ? plan.procedure : plan.strict;
  std::cerr << "plan: " << a.anatomy_path << " target " << a.target << ": " << gw::plan_kind_name(plan.kind)
            << (plan.kind == gw::PlanKind::kNone ? " found, the tip got within " + std::to_string(plan.tip_to_target_mm) + " mm of the target"
                                                 : " plan, " + std::to_string(plan.time_s) + " s, " +
                                                       std::to_string(plan.wrong_entries) + " wrong-branch entries")
            << "; peak tip force " << plan.peak_tip_force_N << " N, peak node force " << plan.peak_node_force_N
            << " N; searched " << plan.strict.env_steps + plan.procedure.env_steps << " env steps in "
            << plan.strict.seconds + plan.procedure.seconds << " s (" << last.maneuvers << " maneuvers in the last search)\n";
  if (plan.kind == gw::PlanKind::kNone) std::cerr << "plan: why: " << plan.why << "\n";
  if (a.print_json) std::cout << doc.dump(1) << "\n";
  return plan.kind == gw::PlanKind::kNone ? 2 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Plan a guidewire procedure to a target: search push, pull and rotation in the simulator"};
  PlanArgs args;
  add_plan_options(app, args);
  CLI11_PARSE(app, argc, argv);
  try {
    return plan_main(args);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
