// bench-policy --policy F.json: time per action of the Eigen actor; prints one JSON object.
#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>

#include "policy/load_actor.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark the Eigen SAC actor"};
  std::string policy;
  long calls = 100000;
  app.add_option("--policy", policy, "actor JSON file")->required();
  app.add_option("--calls", calls, "number of timed act() calls");
  CLI11_PARSE(app, argc, argv);
  try {
    gw::ActorMLP actor = gw::load_actor(policy);
    std::mt19937 rng(0);
    std::normal_distribution<float> nd;
    Eigen::VectorXf obs(actor.obs_size()), action(actor.action_size());
    for (int i = 0; i < obs.size(); ++i) obs[i] = nd(rng);
    for (int i = 0; i < 1000; ++i) actor.act(obs, action);  // warm-up
    float sink = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (long i = 0; i < calls; ++i) {
      obs[i % obs.size()] += 1e-6f;  // keep the compiler from hoisting the call
      actor.act(obs, action);
      sink += action[0];
    }
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::json out = {{"runtime", "eigen"},      {"policy", policy},
                          {"obs_size", actor.obs_size()}, {"action_size", actor.action_size()},
                          {"calls", calls},          {"ns_per_action", ns / static_cast<double>(calls)},
                          {"us_per_action", ns / static_cast<double>(calls) / 1000.0},
                          {"checksum", sink}};
    std::cout << out.dump() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "bench-policy: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
