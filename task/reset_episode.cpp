// reset_episode (episode.hpp): a seeded start at the inlet.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "task/episode_stages.hpp"

namespace gw {

namespace {

constexpr double kPi = 3.14159265358979323846;

// splitmix64: a tiny, portable generator, so episodes replay identically on every platform
// (std::uniform_real_distribution is implementation-defined).
struct SplitMix64 {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

}  // namespace

EpisodeState reset_episode(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed) {
  const TaskConfig& c = task.config;
  SplitMix64 rng{seed};
  const int n_anatomies = static_cast<int>(task.anatomies.size());
  const int a = anatomy < 0 ? rng.below(n_anatomies) : anatomy;
  if (a >= n_anatomies)
    throw std::invalid_argument("anatomy index " + std::to_string(anatomy) + " does not exist; valid are 0.." +
                                std::to_string(n_anatomies - 1));
  const auto& courses = task.courses[static_cast<size_t>(a)];
  const int n_targets = static_cast<int>(courses.size());
  const int t = target_id == 0 ? 1 + rng.below(n_targets) : target_id;
  if (t < 1 || t > n_targets)
    throw std::invalid_argument("target " + std::to_string(target_id) + " does not exist in " +
                                task.anatomies[static_cast<size_t>(a)].name + "; valid targets are 1.." +
                                std::to_string(n_targets));
  EpisodeState s;
  s.anatomy = a;
  s.target_id = t;
  s.seed = seed;
  s.course = &courses[static_cast<size_t>(t - 1)];
  s.start_rotation_rad = 2.0 * kPi * rng.uniform();
  s.start_tilt_rad = c.max_start_tilt_rad * rng.uniform();
  const double azimuth = 2.0 * kPi * rng.uniform();

  const CenterlineGraph& g = task.anatomies[static_cast<size_t>(a)].graph;
  const Eigen::Vector3d d = g.inlet_direction.normalized();
  const Eigen::Vector3d e1 = d.unitOrthogonal();
  const Eigen::Vector3d e2 = d.cross(e1);
  const Eigen::Vector3d axis = std::cos(azimuth) * e1 + std::sin(azimuth) * e2;
  const Eigen::Vector3d direction = Eigen::AngleAxisd(s.start_tilt_rad, axis) * d;
  s.wire = make_initial_state(wire_of(task, a), g.inlet.position, direction, s.start_rotation_rad, c.initial_insertion_mm);

  const double advance = env_dt(c) * c.push_mm_per_s;
  s.max_steps = c.max_steps > 0 ? c.max_steps
                                : static_cast<int>(std::ceil(c.max_steps_path_factor * s.course->line.length / advance)) + 50;
  observe_episode(task, s, true);
  s.obs[obs_index::kAction] = 0.0;
  s.obs[obs_index::kInsertion] = 1.0;
  s.obs[obs_index::kWrongBranch] = 0.0;
  s.obs[obs_index::kTipForce] = 0.0;
  s.stall.best_progress_mm = s.progress_mm;
  s.depth.deepest_progress_mm = s.progress_mm;
  s.stall.inserted_at_best_mm = s.wire.inserted_length_mm;
  s.procedure.max_steps =
      s.max_steps + (c.recovery_attempts > 0 ? static_cast<int>(std::ceil(c.recovery_time_s / env_dt(c))) : 0);
  return s;
}

}  // namespace gw
