// policy-run --policy F.json: one observation per stdin line -> one action per stdout line.
// The language-neutral parity check for the Eigen actor.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "policy/load_actor.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Run the exported SAC actor on observations read from stdin"};
  std::string policy;
  app.add_option("--policy", policy, "actor JSON file")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    gw::ActorMLP actor = gw::load_actor(policy);
    Eigen::VectorXf obs(actor.obs_size()), action(actor.action_size());
    std::string line;
    long lineno = 0;
    while (std::getline(std::cin, line)) {
      ++lineno;
      std::istringstream in(line);
      std::string tok;
      int n = 0;
      while (in >> tok) {
        char* end = nullptr;
        const float v = std::strtof(tok.c_str(), &end);
        if (end == tok.c_str() || *end != '\0') {
          std::cerr << "policy-run: stdin line " << lineno << ": not a number: '" << tok << "'\n";
          return 2;
        }
        if (n < actor.obs_size()) obs[n] = v;
        ++n;
      }
      if (n == 0) continue;  // blank line
      if (n != actor.obs_size()) {
        std::cerr << "policy-run: stdin line " << lineno << ": " << n << " values, the policy expects "
                  << actor.obs_size() << "\n";
        return 2;
      }
      actor.act(obs, action);
      for (int i = 0; i < action.size(); ++i) std::printf(i ? " %.9g" : "%.9g", static_cast<double>(action[i]));
      std::printf("\n");
    }
  } catch (const std::exception& e) {
    std::cerr << "policy-run: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
