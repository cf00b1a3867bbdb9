// bench-env: env steps/s in process vs through guidewire-server's socket protocol, and the
// overhead in percent (goal < 5%). Prints ONE JSON object.
#include <CLI/CLI.hpp>
#include <iostream>
#include <nlohmann/json.hpp>

#include "lib/server/env_benchmark.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark: navigation env steps/s in process vs through the socket"};
  std::string anatomies = "train", index = gw::default_anatomy_index();
  int steps = 400;
  std::uint64_t seed = 0;
  app.add_option("--anatomies", anatomies, "anatomy sets, names or mesh paths")->capture_default_str();
  app.add_option("--index", index, "anatomy index JSON")->capture_default_str();
  app.add_option("--steps", steps, "env steps each way")->capture_default_str();
  app.add_option("--seed", seed, "first episode seed")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    const gw::NavigationTask task =
        gw::make_navigation_task(gw::TaskConfig{}, gw::default_wire_params(), gw::load_anatomies(anatomies, index));
    const gw::EnvBenchmark b = gw::run_env_benchmark(task, steps, seed);
    const nlohmann::json j = {{"benchmark", "env"},
                              {"anatomies", anatomies},
                              {"steps", b.steps},
                              {"episodes", b.episodes},
                              {"frame_skip", task.config.frame_skip},
                              {"inprocess_steps_per_s", b.inprocess_steps_per_s},
                              {"socket_steps_per_s", b.socket_steps_per_s},
                              {"overhead_percent", b.overhead_percent},
                              {"overhead_us_per_step", b.overhead_us_per_step},
                              {"median_overhead_us_per_step", b.median_overhead_us_per_step},
                              {"median_overhead_percent", b.median_overhead_percent}};
    std::cout << j.dump() << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench-env: " << e.what() << std::endl;
    return 1;
  }
}
