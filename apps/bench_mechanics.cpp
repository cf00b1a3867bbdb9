// bench-mechanics [--anatomy STEM] [--push MM_PER_S] [--length MM] [--params F.json] [--friction-torque]: mechanics speed.
// Prints one JSON object: a full insertion into a committed anatomy (coronary by default) with the
// per-stage breakdown, and the cost per integration sub-step for 50, 100, 200 and 400 nodes.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "engine/mesh/load_mesh.hpp"
#include "engine/sim/mechanics_benchmark.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark the guidewire mechanics"};
  std::string stem = "anatomies/test/coronary/coronary";  // relative to the repository root
  double push = 20.0, length = 100.0, roll = 0.0;
  int scaling_substeps = 2000;
  std::string params_path;
  bool friction_torque = false;
  app.add_option("--anatomy", stem, "anatomy path without extension (STEM.stl, STEM.truth.json)");
  app.add_option("--push", push, "insertion speed [mm/s]");
  app.add_option("--length", length, "inserted length to reach [mm]");
  app.add_option("--roll", roll, "initial axial roll [rad]");
  app.add_option("--scaling-substeps", scaling_substeps, "timed sub-steps per node count");
  app.add_option("--params", params_path, "wire parameter JSON (default: the built-in 0.014 inch wire)");
  app.add_flag("--friction-torque", friction_torque, "friction at the wire surface (turns the wire; default off)");
  CLI11_PARSE(app, argc, argv);
  try {
    std::ifstream in(stem + ".truth.json");
    if (!in) throw std::runtime_error(stem + ".truth.json: cannot open");
    nlohmann::json truth;
    in >> truth;
    Eigen::Vector3d inlet, dir;
    for (int i = 0; i < 3; ++i) {
      inlet[i] = truth.at("inlet").at("position").at(i).get<double>();
      dir[i] = truth.at("inlet").at("direction").at(i).get<double>();
    }
    const gw::VesselScene scene = gw::make_vessel_scene(gw::load_valid_mesh(stem + ".stl"));
    gw::WireParams params = params_path.empty() ? gw::default_wire_params() : gw::load_wire_params(params_path);
    if (friction_torque) params.friction_torque = true;
    const gw::WireModel model = gw::make_wire_model(params, 0.01);
    const gw::InsertionBenchmark b = gw::run_insertion_benchmark(model, scene, inlet, dir, roll, push, length);
    const double sub = b.substeps > 0 ? b.substeps : 1;
    auto us = [&](double s) { return 1e6 * s / sub; };
    nlohmann::json stages = {{"detect_us", us(b.stages.detect_s)},
                             {"assemble_us", us(b.stages.assemble_s)},
                             {"solve_us", us(b.stages.solve_s)},
                             {"constraints_us", us(b.stages.constraints_s)}};
    nlohmann::json scaling = nlohmann::json::array();
    for (const gw::ScalingPoint& p : gw::run_scaling_benchmark({50, 100, 200, 400}, scaling_substeps))
      scaling.push_back({{"nodes", p.nodes}, {"free_nodes", p.free_nodes}, {"us_per_substep", p.us_per_substep}});
    nlohmann::json out = {
        {"anatomy", stem},
        {"mesh_triangles", scene.mesh.F.rows()},
        {"wire_nodes", model.nodes},
        {"dt_s", model.dt},
        {"substeps_per_step", model.substeps},
        {"push_mm_per_s", push},
        {"friction_torque", model.params.friction_torque},
        {"insertion",
         {{"ok", b.ok},
          {"problem", b.problem},
          {"inserted_mm", b.inserted_mm},
          {"free_nodes_at_end", b.free_nodes_end},
          {"control_steps", b.control_steps},
          {"substeps", b.substeps},
          {"control_steps_per_s", b.control_steps / b.seconds},
          {"substeps_per_s", b.substeps / b.seconds},
          {"mean_contacts", b.mean_contacts},
          {"max_contacts", b.max_contacts},
          {"mean_max_pgs_sweeps", b.mean_pgs_sweeps},
          {"max_penetration_mm", b.max_penetration_mm},
          {"split_substeps", b.split_substeps},
          {"us_per_substep_by_stage", stages},
          {"tip", {b.tip.x(), b.tip.y(), b.tip.z()}}}},
        {"scaling_free_space", scaling}};
    std::cout << out.dump() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "bench-mechanics: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
