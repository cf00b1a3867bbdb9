// torque-transmission [--mu 0,0.05,0.1] [--turn-seconds S] [--friction-torque on|off|both] [--out F.json]:
// the wire laid through a tube with three 90-degree bends (engine/sim/torque_transmission.hpp), its
// proximal end turned through a full turn and back; prints one JSON object per run (summary and the
// proximal/tip roll series) as one array, and writes it to --out. scripts/plot_torque_transmission.py
// draws the figure.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/sim/torque_transmission.hpp"

namespace {

// --mu's comma-separated friction coefficients (std::stod: throws on a non-number).
std::vector<double> parse_mus(const std::string& mus_text) {
  std::vector<double> mus;
  std::stringstream ss(mus_text);
  for (std::string item; std::getline(ss, item, ',');) mus.push_back(std::stod(item));
  return mus;
}

// --friction-torque as the settings to run (on, off or both, in that order); throws for another word.
std::vector<bool> friction_torque_settings(const std::string& torque) {
  std::vector<bool> settings;
  if (torque == "on" || torque == "both") settings.push_back(true);
  if (torque == "off" || torque == "both") settings.push_back(false);
  if (settings.empty()) throw std::runtime_error("--friction-torque must be on, off or both");
  return settings;
}

// One run's JSON: its settings, summary, per-stage microseconds per sub-step and the roll series.
nlohmann::json run_json(const gw::TorqueTransmission& r, double mu, bool on, double turn_seconds) {
  const double sub = r.substeps > 0 ? static_cast<double>(r.substeps) : 1.0;
  return {{"mu", mu},
          {"friction_torque", on},
          {"turn_seconds", turn_seconds},
          {"ok", r.ok},
          {"problem", r.problem},
          {"max_lag_rad", r.max_lag_rad},
          {"final_lag_rad", r.final_lag_rad},
          {"max_tip_rate_rad_per_s", r.max_tip_rate_rad_per_s},
          {"drive_rate_rad_per_s", 2.0 * M_PI / turn_seconds},
          {"substeps", r.substeps},
          {"substeps_per_s", r.substeps_per_s},
          {"split_substeps", r.split_substeps},
          {"mean_contacts", r.mean_contacts},
          {"mean_max_pgs_sweeps", r.mean_max_pgs_sweeps},
          {"us_per_substep_by_stage",
           {{"detect_us", 1e6 * r.stages.detect_s / sub},
            {"assemble_us", 1e6 * r.stages.assemble_s / sub},
            {"solve_us", 1e6 * r.stages.solve_s / sub},
            {"constraints_us", 1e6 * r.stages.constraints_s / sub}}},
          {"time_s", r.time_s},
          {"proximal_rad", r.proximal_rad},
          {"tip_rad", r.tip_rad}};
}

// Every (friction torque setting, mu) run of the base wire, in that order, each summarised on stderr.
nlohmann::json run_all(const gw::WireParams& base, const std::vector<bool>& settings, const std::vector<double>& mus,
                       double turn_seconds) {
  nlohmann::json runs = nlohmann::json::array();
  for (bool on : settings)
    for (double mu : mus) {
      gw::WireParams p = base;
      p.friction = mu;
      p.friction_torque = on;
      const gw::TorqueTransmission r = gw::run_torque_transmission(p, turn_seconds);
      runs.push_back(run_json(r, mu, on, turn_seconds));
      std::cerr << "mu " << mu << " friction_torque " << on << ": max lag " << r.max_lag_rad << " rad, "
                << r.substeps_per_s << " sub-steps/s" << (r.ok ? "" : " FAILED: " + r.problem) << "\n";
    }
  return runs;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Torque transmission through a tube with three bends"};
  std::string mus_text = "0,0.05,0.1", torque = "both", out_path, params_path;
  double turn_seconds = 2.0;
  app.add_option("--mu", mus_text, "comma-separated friction coefficients");
  app.add_option("--turn-seconds", turn_seconds, "time of one full proximal turn (each way) [s]");
  app.add_option("--friction-torque", torque, "on (friction at the surface), off (the paper's model) or both");
  app.add_option("--params", params_path, "wire parameter JSON (default: the built-in 0.014 inch wire)");
  app.add_option("--out", out_path, "write the JSON here too");
  CLI11_PARSE(app, argc, argv);
  try {
    const std::vector<double> mus = parse_mus(mus_text);
    const std::vector<bool> settings = friction_torque_settings(torque);
    const gw::WireParams base = params_path.empty() ? gw::default_wire_params() : gw::load_wire_params(params_path);
    const nlohmann::json runs = run_all(base, settings, mus, turn_seconds);
    std::cout << runs.dump() << "\n";
    if (!out_path.empty()) std::ofstream(out_path) << runs.dump(1) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "torque-transmission: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
