#pragma once
// Is a target reachable by rotation alone? Runs the rotation schedules (rotation_schedules.hpp) from
// a few seeded starts and stops at the first success. "Not reached" is evidence, not proof: a cleverer
// rotation could still get in, but none of a family that spins, aims both ways and sweeps did.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "task/navigation_task.hpp"

namespace gw {

struct ReachabilityCase {
  int anatomy = 0;    // index into task.anatomies
  int target_id = 0;
  std::uint64_t first_seed = 0;  // starts tried: first_seed .. first_seed + seeds - 1
};

struct Reachability {
  bool reachable = false;
  std::string schedule;     // the first schedule that got in ("" when none did)
  std::uint64_t seed = 0;   // and its seed
  int episodes = 0;         // episodes run
  std::string error;        // set when an episode threw (the case is then not judged reachable)
};

// Schedules in rotation_schedule_names() order, each from the case's seeds; cases run in parallel on
// `threads` threads. Results in case order.
std::vector<Reachability> probe_reachability(const NavigationTask& task, const std::vector<ReachabilityCase>& cases,
                                             int seeds, int threads);

nlohmann::json to_json(const Reachability& r);

}  // namespace gw
