#include "engine/sim/mechanics_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <ctime>

namespace gw {

namespace {

// Folds the bytes of `value` into the FNV-1a hash `h`.
template <class T>
void hash_bytes(std::uint64_t& h, const T& value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (unsigned char b : bytes) h = (h ^ b) * 0x100000001b3ULL;
}

// Folds the wire's state and the step's contact count into the trajectory hash.
void hash_step(std::uint64_t& h, const WireState& state, int contacts) {
  for (std::size_t i = 0; i < state.x.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      hash_bytes(h, state.x[i][a]);
      hash_bytes(h, state.v[i][a]);
      hash_bytes(h, state.w[i][a]);
    }
    for (int a = 0; a < 4; ++a) hash_bytes(h, state.q[i].coeffs()[a]);
  }
  hash_bytes(h, contacts);
}

// One insertion in progress: its wire, its figures so far, and whether it has ended.
struct InsertionRun {
  WireState state;
  InsertionBenchmark b;
  double contact_sum = 0, sweep_sum = 0;
  bool done = false;
};

InsertionRun start_insertion(const WireModel& model, const Eigen::Vector3d& inlet, const Eigen::Vector3d& direction,
                             double roll_rad) {
  InsertionRun r;
  r.state = make_initial_state(model, inlet, direction, roll_rad, 2.0);
  return r;
}

// One control step of `run` (timed), or none once it has reached `length_mm` or failed.
void advance_insertion(const WireModel& model, const VesselScene& scene, double push_mm_per_s, double length_mm,
                       InsertionRun& run) {
  if (run.done || run.state.inserted_length_mm >= length_mm) {
    run.done = true;
    return;
  }
  InsertionBenchmark& b = run.b;
  const Control control{push_mm_per_s, 0.0};
  timespec c0{}, c1{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
  const auto t0 = std::chrono::steady_clock::now();
  const StepReport rep = step(model, &scene, control, run.state);
  b.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
  b.cpu_seconds += static_cast<double>(c1.tv_sec - c0.tv_sec) + 1e-9 * static_cast<double>(c1.tv_nsec - c0.tv_nsec);
  ++b.control_steps;
  b.substeps += model.substeps;
  b.stages.detect_s += rep.timings.detect_s;
  b.stages.assemble_s += rep.timings.assemble_s;
  b.stages.solve_s += rep.timings.solve_s;
  b.stages.constraints_s += rep.timings.constraints_s;
  run.contact_sum += rep.contacts;
  run.sweep_sum += rep.contact_iterations;
  b.max_contacts = std::max(b.max_contacts, rep.contacts);
  b.max_penetration_mm = std::max(b.max_penetration_mm, rep.max_penetration_mm);
  b.split_substeps += rep.split_substeps;
  b.long_substeps += rep.long_substeps;
  b.contact_solves += rep.contact_solves;
  b.capped_contact_solves += rep.capped_contact_solves;
  b.contact_checks.insert(b.contact_checks.end(), rep.contact_checks.begin(), rep.contact_checks.end());
  b.free_nodes_end = rep.free_nodes;
  hash_step(b.trajectory_hash, run.state, rep.contacts);
  if (!rep.ok) {
    b.ok = false;
    b.problem = rep.problem;
    run.done = true;
  }
}

InsertionBenchmark finish_insertion(InsertionRun& run) {
  InsertionBenchmark b = run.b;
  b.mean_contacts = b.control_steps > 0 ? run.contact_sum / b.control_steps : 0;
  b.mean_pgs_sweeps = b.control_steps > 0 ? run.sweep_sum / b.control_steps : 0;
  b.inserted_mm = run.state.inserted_length_mm;
  b.tip = run.state.x.back();
  return b;
}

}  // namespace

InsertionBenchmark run_insertion_benchmark(const WireModel& model, const VesselScene& scene,
                                           const Eigen::Vector3d& inlet, const Eigen::Vector3d& direction,
                                           double roll_rad, double push_mm_per_s, double length_mm) {
  InsertionRun run = start_insertion(model, inlet, direction, roll_rad);
  while (!run.done) advance_insertion(model, scene, push_mm_per_s, length_mm, run);
  return finish_insertion(run);
}

std::vector<InsertionBenchmark> run_insertion_benchmarks_interleaved(
    const WireModel& model, const std::vector<const VesselScene*>& scenes, const Eigen::Vector3d& inlet,
    const Eigen::Vector3d& direction, double roll_rad, double push_mm_per_s, double length_mm, int chunk) {
  std::vector<InsertionRun> runs;
  for (std::size_t i = 0; i < scenes.size(); ++i) runs.push_back(start_insertion(model, inlet, direction, roll_rad));
  for (bool any = true; any;) {
    any = false;
    for (std::size_t i = 0; i < scenes.size(); ++i)
      for (int k = 0; k < std::max(1, chunk) && !runs[i].done; ++k) {
        advance_insertion(model, *scenes[i], push_mm_per_s, length_mm, runs[i]);
        any = any || !runs[i].done;
      }
  }
  std::vector<InsertionBenchmark> out;
  for (InsertionRun& run : runs) out.push_back(finish_insertion(run));
  return out;
}

std::vector<ScalingPoint> run_scaling_benchmark(const std::vector<int>& node_counts, int substeps) {
  std::vector<ScalingPoint> out;
  for (int n : node_counts) {
    WireParams p = default_wire_params();
    p.fine_region_mm = 0;  // uniform elements so the node count is exactly n
    p.element_length_mm = p.length_mm / (n - 1);
    p.tip_element_length_mm = p.element_length_mm;
    p.tip_length_mm = std::max(p.tip_length_mm, p.element_length_mm);
    p.max_substep_s = 0.01;  // time sub-steps one by one
    const WireModel model = make_wire_model(p, 0.01);
    WireState state = make_initial_state(model, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0,
                                         p.length_mm - 2.0 * p.element_length_mm - 1.0);
    const Control control{0.0, 2.0};
    for (int i = 0; i < 20; ++i) step(model, nullptr, control, state);  // warm-up (workspace sizing)
    int free_nodes = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < substeps; ++i) free_nodes = step(model, nullptr, control, state).free_nodes;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.push_back({model.nodes, free_nodes, 1e6 * s / substeps});
  }
  return out;
}

}  // namespace gw
