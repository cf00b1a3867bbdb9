// guidewire-server: serves the navigation environment over TCP, newline-delimited JSON, one
// environment per connection (protocol in apps/server/env_session.hpp). The first stdout line is
// {"port": N} (useful with --port 0), then the server runs until SIGINT/SIGTERM.
#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>

#include "apps/runner/heart_motion.hpp"
#include "apps/runner/navigation_anatomy.hpp"
#include "apps/server/tcp_server.hpp"
#include "engine/task/navigation_task.hpp"
#include "engine/task/observation.hpp"

namespace {
gw::TcpServer* g_server = nullptr;
void on_signal(int) {
  if (g_server) g_server->request_stop();
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Guidewire navigation environment server (JSON lines over TCP)"};
  gw::ServerOptions options;
  std::string anatomies = "train", index = gw::default_anatomy_index(), wire_json, control_mode = "auto",
              omega_plane = gw::omega_plane_name(gw::TaskConfig{}.observation.omega_plane),
              junctions = gw::junction_model_name(gw::TaskConfig{}.observation.junctions),
              task_scale = gw::task_scale_name(gw::TaskConfig{}.task_scale);
  gw::TaskConfig config;
  app.add_option("--port", options.port, "TCP port; 0 picks a free one (printed as the first stdout line)")->required();
  app.add_option("--host", options.host, "address to listen on")->capture_default_str();
  app.add_option("--anatomies", anatomies,
                 "comma-separated anatomy sets (train, test, sensitivity), names from the index, or mesh paths")
      ->capture_default_str();
  app.add_option("--index", index, "anatomy index JSON")->capture_default_str();
  app.add_option("--wire", wire_json, "wire parameter JSON (default: 0.014\" coronary wire)");
  app.add_option("--control", control_mode, "when the action applies: always, near_bifurcation, auto")
      ->capture_default_str();
  app.add_option("--omega-plane", omega_plane,
                 "omega's plane: approach (obs/2) or correct_branch (the paper's, obs/1)")
      ->capture_default_str();
  app.add_flag("--omega-side", config.observation.omega_side,
               "also observe omega's sine, on which side of the wrong branch the tip bends (layout obs/3; "
               "needs --omega-plane approach)");
  app.add_option("--junctions", junctions,
                 "how a junction's wrong branches enter omega: separate (the paper's), combined (k-way junctions and "
                 "closely spaced forks aimed at together; with --omega-side: layout obs/4) or kway (k-way junctions "
                 "only, close forks apart; layout obs/6); docs/junctions.md")
      ->capture_default_str();
  bool push_pull = false;
  app.add_flag("--push-pull", push_pull,
               "the actor also sets the insertion speed: action [rotation, insertion] (layout act/2) and observation "
               "obs/5 (obs/3 with the insertion and a wrong-branch flag; docs/recovery.md)");
  bool since_progress = false;
  app.add_flag("--since-progress", since_progress,
               "with --push-pull: observation obs/7 (obs/5 and the time since the tip last progressed; "
               "engine/task/observation.hpp)");
  app.add_option("--recovery", config.recovery_attempts,
                 "the procedure goes on after the strict end, at most K retries (docs/recovery.md; with --push-pull the "
                 "actor pulls back itself)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--recovery-assist", config.recovery_assist,
               "with --recovery and --push-pull: the wrapper pulls the wire back on a stall, after stuck_steps env "
               "steps in a wrong child or standing still after the strict end (docs/recovery.md \"Assisted recovery\")");
  app.add_option("--reward-wrong-branch", config.reward_wrong_branch,
                 "--push-pull: reward lost per env step while the tip is in a wrong child")
      ->capture_default_str();
  app.add_option("--reward-time", config.reward_time_per_step,
                 "--push-pull: reward lost every env step, a cost of time (0: stopping is free; engine/task/reward.hpp)")
      ->capture_default_str();
  app.add_option("--reward-force", config.reward_force_per_N,
                 "reward lost per newton of the env step's peak total wall force (0: the paper's reward; any action "
                 "layout; docs/recovery.md)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--force-limit", config.force_limit_N,
                 "withhold the forward push while the wire presses the wall harder than this many newtons at one node "
                 "(0: off, the paper's task; any action layout; docs/recovery.md \"Force limit\")")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  std::string reward_aim = gw::reward_aim_name(config.reward_aim);
  app.add_option("--reward-aim", reward_aim,
                 "--push-pull: the orientation term times the step's new depth (depth) or its change over the step "
                 "(change; engine/task/reward.hpp says why)")
      ->capture_default_str();
  app.add_option("--task-scale", task_scale,
                 "wrong-branch and control-zone lengths: fixed (the paper's millimetres), vessel (from the walls), "
                 "auto (vessel for an inlet wider than 4 mm in radius; docs/vessel_scale.md)")
      ->capture_default_str();
  app.add_option("--reward-omega-centre", config.reward.omega_centre,
                 "centre of the reward's omega sigmoid (paper Eq. 3: 0.1)")
      ->capture_default_str();
  app.add_option("--reward-omega-slope", config.reward.omega_slope,
                 "slope of the reward's omega sigmoid (paper Eq. 3: 5)")
      ->capture_default_str();
  app.add_option("--push-speed", config.push_mm_per_s, "constant insertion speed at the proximal end, mm/s")
      ->capture_default_str();
  app.add_option("--roll-disturbance", config.roll_disturbance_probability,
                 "training robustness: per-episode probability of an unannounced proximal roll of 45-180 deg "
                 "(0 = the paper's task)")
      ->capture_default_str();
  app.add_option("--random-start", config.random_start_probability,
                 "training: per-episode probability of starting part-way along the access vessel (wire pushed "
                 "without rotation to a random depth before the first bifurcation; 0 = the paper's task)")
      ->capture_default_str();
  gw::HeartSettings heart;
  app.add_option("--heart-rate", heart.heart_rate_bpm,
                 "every anatomy beats at this rate, bpm (0 = static; docs/beating_heart.md), following --motion or its "
                 "own field (STEM.motion.json or the spec's deformation beside its mesh)")
      ->check(CLI::Range(0.0, 300.0));
  app.add_option("--motion", heart.motion_path, "cardiac motion JSON for every anatomy (docs/beating_heart.md)");
  app.add_option("--step-time-limit", options.session.step_time_limit_s,
                 "seconds one env step may run before it is cut off with an error (0 = none)")
      ->capture_default_str();
  app.add_option("--max-line", options.max_line_bytes, "longest accepted request line in bytes")->capture_default_str();
  app.add_option("--seed", options.seed, "seed stream for resets sent without a seed")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    config.control_mode = gw::parse_control_mode(control_mode);
    config.observation.omega_plane = gw::parse_omega_plane(omega_plane);
    config.observation.junctions = gw::parse_junction_model(junctions);
    config.reward_aim = gw::parse_reward_aim(reward_aim);
    config.task_scale = gw::parse_task_scale(task_scale);
    if (push_pull) {
      config.action = gw::ActionLayout::kRotationInsertion;
      config.observation.omega_side = config.observation.push_pull = true;
    }
    config.observation.since_progress = since_progress;
    config.observation.name();  // refuses omega_side in the paper's plane, naming why
    const gw::WireParams wire = wire_json.empty() ? gw::default_wire_params() : gw::load_wire_params(wire_json);
    std::vector<gw::Anatomy> loaded = gw::load_indexed_anatomies(anatomies, index);
    for (gw::Anatomy& a : loaded) gw::apply_heart_settings(a, heart);  // no-op without --heart-rate / --motion
    const gw::NavigationTask task = gw::make_navigation_task(config, wire, std::move(loaded));
    gw::TcpServer server(task, options);
    g_server = &server;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::signal(SIGPIPE, SIG_IGN);
    std::cout << "{\"port\": " << server.port() << "}" << std::endl;
    std::cerr << "guidewire-server: " << task.anatomies.size() << " anatomies, listening on " << options.host << ":"
              << server.port() << std::endl;
    server.serve();
    server.stop();
    g_server = nullptr;
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "guidewire-server: " << e.what() << std::endl;
    return 1;
  }
}
