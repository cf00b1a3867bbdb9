#pragma once
// Timing runs behind `bench-mechanics`: a full insertion into a vessel and the per-step cost versus the
// number of nodes. Wall-clock figures, for reporting only (never asserted in tests).
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/scene/vessel_scene.hpp"
#include "engine/sim/step.hpp"

namespace gw {

struct InsertionBenchmark {
  int control_steps = 0, substeps = 0;
  double seconds = 0;                 // wall time inside step()
  double cpu_seconds = 0;             // this thread's CPU time inside step() (steadier on a shared machine)
  StepTimings stages;                 // summed over the run
  double mean_contacts = 0;           // per sub-step (last sub-step of each control step)
  int max_contacts = 0;
  double mean_pgs_sweeps = 0;         // per control step: the most sweeps any of its sub-steps used
  double max_penetration_mm = 0;
  int split_substeps = 0;  // sub-steps halved: the wire moved too fast, or a long one met the wall
  int long_substeps = 0;   // sub-steps longer than the model's h taken (adaptive stepping in free lumen)
  int contact_solves = 0, capped_contact_solves = 0;  // StepReport's, summed over the run
  std::vector<ContactForceError> contact_checks;       // model.reference_contact_solve_every > 0: StepReport's
  double inserted_mm = 0;
  int free_nodes_end = 0;
  bool ok = true;
  std::string problem;
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  // FNV-1a hash of the bits of every node's x, q, v, w and of the contact count after each control step:
  // two builds whose hashes agree ran bit-identical trajectories (checks that an optimisation is exact).
  std::uint64_t trajectory_hash = 0xcbf29ce484222325ULL;
};

// Pushes the wire at `push_mm_per_s` from `inlet` along `direction` (roll `roll_rad`) until
// `length_mm` is inserted or the simulation reports a problem.
InsertionBenchmark run_insertion_benchmark(const WireModel& model, const VesselScene& scene,
                                           const Eigen::Vector3d& inlet, const Eigen::Vector3d& direction,
                                           double roll_rad, double push_mm_per_s, double length_mm);

// run_insertion_benchmark in each of `scenes` (the same wire and insertion), advanced in turn `chunk`
// control steps at a time in this thread: a change of the machine's speed during the run (another job, a
// shared core) weighs on every scene alike, so their steps per second compare as a ratio. Each result
// is run_insertion_benchmark's (the physics does not depend on the interleaving; only the timings do).
std::vector<InsertionBenchmark> run_insertion_benchmarks_interleaved(
    const WireModel& model, const std::vector<const VesselScene*>& scenes, const Eigen::Vector3d& inlet,
    const Eigen::Vector3d& direction, double roll_rad, double push_mm_per_s, double length_mm, int chunk);

struct ScalingPoint {
  int nodes = 0, free_nodes = 0;
  double us_per_substep = 0;          // assemble + solve of the free wire (no contact)
};

// Cost per integration sub-step of a uniform 310 mm wire discretised with each node count in
// `node_counts`, almost fully inserted, rotating in free space.
std::vector<ScalingPoint> run_scaling_benchmark(const std::vector<int>& node_counts, int substeps);

}  // namespace gw
