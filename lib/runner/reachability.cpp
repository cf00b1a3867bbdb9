#include "lib/runner/reachability.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>

#include "lib/runner/rotation_schedules.hpp"
#include "lib/runner/run_episode.hpp"

namespace gw {
namespace {

Reachability probe_one(const NavigationTask& task, const ReachabilityCase& c, int seeds) {
  Reachability r;
  TraceOptions trace;
  trace.wire_shape_every = 0;
  for (const std::string& name : rotation_schedule_names())
    for (int k = 0; k < seeds; ++k) {
      const std::uint64_t seed = c.first_seed + static_cast<std::uint64_t>(k);
      auto schedule = make_rotation_schedule(name);
      ++r.episodes;
      if (run_episode(task, c.anatomy, c.target_id, seed, *schedule, trace).outcome == "success") {
        r.reachable = true;
        r.schedule = name;
        r.seed = seed;
        return r;
      }
    }
  return r;
}

}  // namespace

std::vector<Reachability> probe_reachability(const NavigationTask& task, const std::vector<ReachabilityCase>& cases,
                                             int seeds, int threads) {
  std::vector<Reachability> out(cases.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < cases.size(); i = next++) {
      try {
        out[i] = probe_one(task, cases[i], seeds);
      } catch (const std::exception& e) {  // a worker thread must not throw: keep it with the case
        out[i].error = e.what();
      }
    }
  };
  const int n = std::max(1, std::min<int>(threads, static_cast<int>(cases.size())));
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return out;
}

nlohmann::json to_json(const Reachability& r) {
  nlohmann::json j = {{"reachable", r.reachable}, {"episodes", r.episodes}};
  if (r.reachable) j["reached_by"] = {{"schedule", r.schedule}, {"seed", r.seed}};
  if (!r.error.empty()) j["error"] = r.error;
  return j;
}

}  // namespace gw
