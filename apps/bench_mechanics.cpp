// bench-mechanics [--anatomy STEM] [--push MM_PER_S] [--length MM] [--params F.json] [--friction-torque]
//                 [--heart-rate BPM [--motion FILE]] [--contact-accuracy K]: mechanics speed.
// Prints one JSON object: a full insertion into a committed anatomy (coronary by default) with the
// per-stage breakdown and a hash of its trajectory (bit-identity checks of optimisations), and the cost
// per integration sub-step for 50, 100, 200 and 400 nodes. With a heart rate, the same insertion again
// in the beating vessel (issue 36) in the same run, under "beating", with its steps per second against
// the static run's (by wall time, and by CPU time; the two insertions run in turn, ten control steps
// each, so that the machine's changing speed cancels in the ratio). The motion: FILE (a cardiac motion
// JSON, engine/scene/wall_motion.hpp), or by default the generator's coronary field (12% radial
// contraction, 10% axial shortening, 2.5 deg/cm twist about -z through the origin: the field of
// anatomies/test/coronary_deformed) held still at the inlet (the guide catheter's frame).
// With --contact-accuracy K, the static insertion once more, untimed, with every K-th sub-step's contact
// problem also solved to convergence (on a copy: the same trajectory, checked by its hash): how far the
// forces of the capped projected Gauss-Seidel solve are from the converged ones, under "contact_accuracy".
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "base/mesh/load_mesh.hpp"
#include "base/util/read_json_file.hpp"
#include "engine/scene/moving_wall.hpp"
#include "engine/sim/mechanics_benchmark.hpp"

namespace {

// Largest vertex displacement of a moving scene at time t [mm].
double largest_displacement(const gw::VesselScene& scene, double t) {
  double d = 0;
  for (Eigen::Index i = 0; i < scene.mesh.V.rows(); ++i)
    d = std::max(d, (gw::wall_vertex_position(*scene.motion, scene.mesh, static_cast<int>(i), t) -
                     scene.mesh.V.row(i).transpose()).norm());
  return d;
}

// What the command line asks for.
struct BenchArgs {
  std::string stem = "anatomies/test/coronary/coronary";  // relative to the repository root
  double push = 20.0, length = 100.0, roll = 0.0;
  int scaling_substeps = 2000;
  std::string params_path;
  bool friction_torque = false;
  double heart_rate = 0;
  std::string motion_path;
  int contact_accuracy = 0;
};

// The flags, into `a` (defaults as above).
void add_bench_options(CLI::App& app, BenchArgs& a) {
  app.add_option("--anatomy", a.stem, "a generated anatomy: STEM or STEM.stl (its STEM.truth.json gives the inlet)");
  app.add_option("--push", a.push, "insertion speed [mm/s]");
  app.add_option("--length", a.length, "inserted length to reach [mm]");
  app.add_option("--roll", a.roll, "initial axial roll [rad]");
  app.add_option("--scaling-substeps", a.scaling_substeps, "timed sub-steps per node count");
  app.add_option("--params", a.params_path, "wire parameter JSON (default: the built-in 0.014 inch wire)");
  app.add_flag("--friction-torque", a.friction_torque, "friction at the wire surface (turns the wire; default off)");
  app.add_option("--heart-rate", a.heart_rate, "also run the insertion in the beating vessel at this rate [bpm]");
  app.add_option("--motion", a.motion_path, "cardiac motion JSON (default: the generator's coronary field)");
  app.add_option("--contact-accuracy", a.contact_accuracy,
                 "also run the static insertion untimed, every K-th sub-step's contact problem solved to convergence "
                 "as well: the capped solve's force errors (0 = off)")
      ->check(CLI::NonNegativeNumber);
}

// The insertion point and direction of the generated anatomy STEM (its STEM.truth.json); throws naming the file.
void read_inlet(const std::string& stem, Eigen::Vector3d& inlet, Eigen::Vector3d& dir) {
  const nlohmann::json truth = gw::read_json_file(stem + ".truth.json", "truth centerline (bench-mechanics runs a generated anatomy: --anatomy STEM with STEM.stl and STEM.truth.json)");
  for (int i = 0; i < 3; ++i) {
    inlet[i] = truth.at("inlet").at("position").at(i).get<double>();
    dir[i] = truth.at("inlet").at("direction").at(i).get<double>();
  }
}

// The wire model the benchmark runs: --params (or the built-in wire), with --friction-torque.
gw::WireModel bench_wire_model(const BenchArgs& a) {
  gw::WireParams params = a.params_path.empty() ? gw::default_wire_params() : gw::load_wire_params(a.params_path);
  if (a.friction_torque) params.friction_torque = true;
  return gw::make_wire_model(params, 0.01);
}

// One insertion's JSON: outcome, rates, contacts, per-stage microseconds per sub-step and the trajectory hash.
nlohmann::json insertion_json(const gw::InsertionBenchmark& b) {
  const double sub = b.substeps > 0 ? b.substeps : 1;
  auto us = [&](double s) { return 1e6 * s / sub; };
  nlohmann::json stages = {{"detect_us", us(b.stages.detect_s)},
                           {"assemble_us", us(b.stages.assemble_s)},
                           {"solve_us", us(b.stages.solve_s)},
                           {"constraints_us", us(b.stages.constraints_s)}};
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(b.trajectory_hash));
  return nlohmann::json{{"ok", b.ok},
                        {"problem", b.problem},
                        {"inserted_mm", b.inserted_mm},
                        {"free_nodes_at_end", b.free_nodes_end},
                        {"control_steps", b.control_steps},
                        {"substeps", b.substeps},
                        {"control_steps_per_s", b.control_steps / b.seconds},
                        {"control_steps_per_cpu_s", b.control_steps / b.cpu_seconds},
                        {"substeps_per_s", b.substeps / b.seconds},
                        {"mean_contacts", b.mean_contacts},
                        {"max_contacts", b.max_contacts},
                        {"mean_max_pgs_sweeps", b.mean_pgs_sweeps},
                        {"max_penetration_mm", b.max_penetration_mm},
                        {"split_substeps", b.split_substeps},
                        {"long_substeps", b.long_substeps},
                        {"contact_solves", b.contact_solves},
                        {"share_contact_solves_at_sweep_cap",
                         b.contact_solves > 0 ? static_cast<double>(b.capped_contact_solves) / b.contact_solves : 0.0},
                        {"us_per_substep_by_stage", stages},
                        {"tip", {b.tip.x(), b.tip.y(), b.tip.z()}},
                        {"trajectory_hash", hash}};
}

// The beating run's motion at --heart-rate: --motion's file (held at the inlet where it says so), or the
// generator's coronary field held still at the inlet.
gw::CardiacMotion bench_cardiac_motion(const BenchArgs& a, const Eigen::Vector3d& inlet) {
  gw::CardiacMotion cm;
  if (!a.motion_path.empty()) {
    cm = gw::load_cardiac_motion(a.motion_path);
    if (cm.hold_inlet) {  // the file's default: held at the inlet, as navigate holds it
      cm.has_fixed_point = true;
      cm.fixed_point = inlet;
    }
  } else {
    cm.axis_origin = Eigen::Vector3d::Zero();
    cm.axis_direction = Eigen::Vector3d(0, 0, -1);
    cm.contraction_mm = 0.12;  // fractions of a 1 mm reference: the generator's 12% and 10%
    cm.reference_radius_mm = 1.0;
    cm.shortening_mm = 0.1;
    cm.reference_length_mm = 1.0;
    cm.twist_deg_per_cm = 2.5;
    cm.has_fixed_point = true;
    cm.fixed_point = inlet;
  }
  cm.heart_rate_bpm = a.heart_rate;
  return cm;
}

// The static and the beating insertion interleaved: out["insertion"] (static) and out["beating"] (its
// motion, end-systolic displacement, insertion and the beating/static rate ratios).
void run_static_and_beating(const BenchArgs& a, const gw::WireModel& model, const gw::VesselScene& scene,
                            const Eigen::Vector3d& inlet, const Eigen::Vector3d& dir, nlohmann::json& out) {
  const gw::CardiacMotion cm = bench_cardiac_motion(a, inlet);
  const gw::VesselScene moving = gw::attach_wall_motion(scene, gw::heart_wall_motion(scene.mesh, cm));
  // The two insertions in turn, kChunk control steps each (about 0.05-0.1 s): a machine that speeds up
  // or slows down during the run (other jobs on a shared core) does so for both.
  const int kChunk = 10;
  const std::vector<gw::InsertionBenchmark> runs = gw::run_insertion_benchmarks_interleaved(
      model, {&scene, &moving}, inlet, dir, a.roll, a.push, a.length, kChunk);
  const gw::InsertionBenchmark &b = runs[0], &bb = runs[1];
  out["insertion"] = insertion_json(b);
  out["beating"] = {{"heart_rate_bpm", a.heart_rate},
                    {"motion", a.motion_path.empty() ? "generator coronary field, fixed at the inlet" : a.motion_path},
                    {"end_systolic_wall_displacement_mm",
                     largest_displacement(moving, 60.0 / a.heart_rate * cm.systole_fraction)},
                    {"insertion", insertion_json(bb)},
                    {"interleaved_control_steps", kChunk},
                    {"control_steps_per_s_beating_over_static",
                     (bb.control_steps / bb.seconds) / (b.control_steps / b.seconds)},
                    // The same by CPU time: on a machine shared with other jobs, wall time also counts the waits.
                    {"control_steps_per_cpu_s_beating_over_static", b.cpu_seconds / bb.cpu_seconds}};
}

// Median, 90th and 99th percentile and largest of `v` (zeros when empty).
nlohmann::json quantiles(std::vector<double> v) {
  if (v.empty()) return {{"median", 0.0}, {"p90", 0.0}, {"p99", 0.0}, {"max", 0.0}};
  std::sort(v.begin(), v.end());
  auto at = [&](double q) { return v[std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()))]; };
  return {{"median", at(0.5)}, {"p90", at(0.9)}, {"p99", at(0.99)}, {"max", v.back()}};
}

// The static insertion again with every k-th sub-step's contact solve checked against a converged one:
// the error quantiles (relative, engine/contact/contact_force_error.hpp) and whether the trajectory is the
// timed run's (`timed_hash`).
nlohmann::json contact_accuracy_json(const BenchArgs& a, gw::WireModel model, const gw::VesselScene& scene,
                                     const Eigen::Vector3d& inlet, const Eigen::Vector3d& dir,
                                     std::uint64_t timed_hash) {
  model.reference_contact_solve_every = a.contact_accuracy;
  const gw::InsertionBenchmark b = gw::run_insertion_benchmark(model, scene, inlet, dir, a.roll, a.push, a.length);
  std::vector<double> resultant, peak_node, distribution;
  int converged = 0;
  for (const gw::ContactForceError& e : b.contact_checks) {
    resultant.push_back(e.resultant);
    peak_node.push_back(e.peak_node);
    distribution.push_back(e.distribution);
    converged += e.reference_converged ? 1 : 0;
  }
  return {{"every_substeps", a.contact_accuracy},
          {"checks", b.contact_checks.size()},
          {"reference_sweep_cap", gw::kReferenceContactSweeps},
          {"reference_converged", converged},
          {"same_trajectory_as_timed_run", b.trajectory_hash == timed_hash},
          {"resultant_error", quantiles(resultant)},
          {"peak_node_force_error", quantiles(peak_node)},
          {"distribution_error", quantiles(distribution)}};
}

// The cost per integration sub-step in free space for 50, 100, 200 and 400 nodes.
nlohmann::json scaling_json(int scaling_substeps) {
  nlohmann::json scaling = nlohmann::json::array();
  for (const gw::ScalingPoint& p : gw::run_scaling_benchmark({50, 100, 200, 400}, scaling_substeps))
    scaling.push_back({{"nodes", p.nodes}, {"free_nodes", p.free_nodes}, {"us_per_substep", p.us_per_substep}});
  return scaling;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Benchmark the guidewire mechanics"};
  BenchArgs a;
  add_bench_options(app, a);
  CLI11_PARSE(app, argc, argv);
  try {
    std::string& stem = a.stem;
    if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".stl") == 0) stem.resize(stem.size() - 4);  // STEM.stl
    Eigen::Vector3d inlet, dir;
    read_inlet(stem, inlet, dir);
    const gw::VesselScene scene = gw::make_vessel_scene(gw::load_valid_mesh(stem + ".stl"));
    const gw::WireModel model = bench_wire_model(a);
    nlohmann::json out;
    if (a.heart_rate <= 0)
      out["insertion"] = insertion_json(gw::run_insertion_benchmark(model, scene, inlet, dir, a.roll, a.push, a.length));
    else
      run_static_and_beating(a, model, scene, inlet, dir, out);
    if (a.contact_accuracy > 0) {
      const std::string hash = out["insertion"]["trajectory_hash"];
      out["contact_accuracy"] = contact_accuracy_json(a, model, scene, inlet, dir, std::stoull(hash, nullptr, 16));
    }
    const nlohmann::json scaling = scaling_json(a.scaling_substeps);
    out["anatomy"] = stem;
    out["mesh_triangles"] = scene.mesh.F.rows();
    out["wire_nodes"] = model.nodes;
    out["dt_s"] = model.dt;
    out["substeps_per_step"] = model.substeps;
    out["free_span"] = model.free_span;
    out["push_mm_per_s"] = a.push;
    out["friction_torque"] = model.params.friction_torque;
    out["scaling_free_space"] = scaling;
    std::cout << out.dump() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "bench-mechanics: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
