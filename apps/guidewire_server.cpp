// guidewire-server: serves the navigation environment over TCP, newline-delimited JSON, one
// environment per connection (protocol in lib/server/env_session.hpp). The first stdout line is
// {"port": N} (useful with --port 0), then the server runs until SIGINT/SIGTERM.
#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>

#include "lib/runner/heart_motion.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "lib/runner/task_options.hpp"
#include "lib/server/tcp_server.hpp"
#include "task/navigation_task.hpp"
#include "task/observation.hpp"

namespace {
gw::TcpServer* g_server = nullptr;
void on_signal(int) {
  if (g_server) g_server->request_stop();
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Guidewire navigation environment server (JSON lines over TCP)"};
  gw::ServerOptions options;
  std::string anatomies = "train", index = gw::default_anatomy_index(), wire_json;
  app.add_option("--port", options.port, "TCP port; 0 picks a free one (printed as the first stdout line)")->required();
  app.add_option("--host", options.host, "address to listen on")->capture_default_str();
  app.add_option("--anatomies", anatomies,
                 "comma-separated anatomy sets (train, test, sensitivity), names from the index, mesh paths, or "
                 "another index's path (a gw-anatomy-pool pool's index.json: every anatomy in it)")
      ->capture_default_str();
  app.add_option("--index", index, "anatomy index JSON")->capture_default_str();
  app.add_option("--wire", wire_json, "wire parameter JSON (default: 0.014\" coronary wire)");
  gw::TaskOptions task_options;
  gw::add_task_options(app, task_options);
  gw::HeartSettings heart;
  app.add_option("--heart-rate", heart.heart_rate_bpm,
                 "every anatomy beats at this rate, bpm (0 = static; docs/beating_heart.md), following --motion or its "
                 "own field (STEM.motion.json or the spec's deformation beside its mesh)")
      ->check(CLI::Range(0.0, 300.0));
  app.add_option("--motion", heart.motion_path, "cardiac motion JSON for every anatomy (docs/beating_heart.md)");
  app.add_option("--step-cutoff", options.session.step_time_limit_s,
                 "seconds of wall time one env step may run before it is cut off with an error reply (0 = none; "
                 "navigate's --step-time-limit ends an episode instead)")
      ->capture_default_str();
  app.add_option("--max-line", options.max_line_bytes, "longest accepted request line in bytes")->capture_default_str();
  app.add_option("--seed", options.seed, "seed stream for resets sent without a seed")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    const gw::TaskConfig config = gw::resolve_task_config(task_options);
    const gw::WireParams wire = wire_json.empty() ? gw::default_wire_params() : gw::load_wire_params(wire_json);
    std::vector<gw::Anatomy> loaded = gw::load_indexed_anatomies(anatomies, index);
    for (gw::Anatomy& a : loaded)  // no-op without --heart-rate / --motion; an index entry's own rate stands
      if (!(a.scene && a.scene->motion)) gw::apply_heart_settings(a, heart);
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
