#include "apps/runner/episode_batch.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <random>
#include <stdexcept>
#include <thread>

namespace gw {
namespace {

std::string valid_targets(int count) {
  return count == 1 ? "the only target is 1" : "valid targets are 1.." + std::to_string(count);
}

}  // namespace

std::vector<EpisodeRequest> plan_episodes(const NavigationTask& task, int anatomy, const std::string& target_spec,
                                          int episodes, std::uint64_t seed) {
  if (anatomy < 0 || anatomy >= static_cast<int>(task.anatomies.size()))
    throw std::invalid_argument("no anatomy with index " + std::to_string(anatomy));
  if (episodes < 1) throw std::invalid_argument("--episodes must be at least 1");
  const int count = static_cast<int>(task.anatomies[static_cast<std::size_t>(anatomy)].graph.targets.size());
  std::vector<EpisodeRequest> out;
  std::uint64_t k = 0;
  auto add = [&](int target) { out.push_back({anatomy, target, seed + k++}); };
  if (target_spec == "all") {
    for (int t = 1; t <= count; ++t)
      for (int e = 0; e < episodes; ++e) add(t);
  } else if (target_spec == "random") {
    std::mt19937_64 rng(seed);  // mt19937_64's output is fixed by the standard: same seed, same targets
    for (int e = 0; e < episodes; ++e) add(1 + static_cast<int>(rng() % static_cast<std::uint64_t>(count)));
  } else {
    std::size_t used = 0;
    int target = 0;
    try {
      target = std::stoi(target_spec, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != target_spec.size())
      throw std::invalid_argument("target '" + target_spec + "' is not a number, 'all' or 'random'");
    if (target < 1 || target > count)
      throw std::invalid_argument("target " + target_spec + " does not exist: " + valid_targets(count));
    for (int e = 0; e < episodes; ++e) add(target);
  }
  return out;
}

std::vector<EpisodeTrace> run_batch(const NavigationTask& task, const std::vector<EpisodeRequest>& requests,
                                    const std::function<std::unique_ptr<Controller>()>& make_controller,
                                    int threads, const TraceOptions& options,
                                    const std::function<void(int, int)>& progress) {
  std::vector<EpisodeTrace> traces(requests.size());
  const int total = static_cast<int>(requests.size());
  const int workers = std::max(1, std::min(threads, total));
  std::atomic<int> next{0}, done{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    try {
      std::unique_ptr<Controller> controller = make_controller();
      for (int i = next++; i < total; i = next++) {
        const EpisodeRequest& r = requests[static_cast<std::size_t>(i)];
        traces[static_cast<std::size_t>(i)] = run_episode(task, r.anatomy, r.target_id, r.seed, *controller, options);
        const int finished = ++done;
        if (progress) progress(finished, total);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = total;  // stop the other workers early
    }
  };
  if (workers == 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (int w = 0; w < workers; ++w) pool.emplace_back(work);
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
  return traces;
}

bool tip_folded_before_loss(const EpisodeTrace& trace) {
  if (trace.outcome != "wrong_branch" || trace.time_s.empty() || trace.observation.size() != trace.time_s.size())
    return false;
  const double end = trace.time_s.back();
  for (std::size_t f = trace.time_s.size(); f-- > 0 && end - trace.time_s[f] <= kFoldWindowS;)
    if (trace.observation[f].size() > obs_index::kTheta && trace.observation[f][obs_index::kTheta] < kFoldedTheta)
      return true;
  return false;
}

nlohmann::json summarize_episodes(const std::vector<EpisodeTrace>& traces) {
  nlohmann::json outcomes = nlohmann::json::object();
  for (const std::string& o : kTraceOutcomes) outcomes[o] = 0;
  nlohmann::json results = nlohmann::json::array();
  int successes = 0;
  for (const EpisodeTrace& t : traces) {
    successes += t.outcome == "success";
    outcomes[t.outcome] = outcomes.value(t.outcome, 0) + 1;
    results.push_back({{"anatomy", t.anatomy},
                       {"controller", t.controller},
                       {"target", t.target_id},
                       {"seed", t.seed},
                       {"outcome", t.outcome},
                       {"detail", t.detail},
                       {"steps", t.time_s.empty() ? 0 : static_cast<int>(t.time_s.size()) - 1},
                       {"sim_time_s", t.time_s.empty() ? 0.0 : t.time_s.back()}});
    if (!std::isnan(t.omega_at_loss)) results.back()["omega_at_loss"] = t.omega_at_loss;
    if (t.outcome == "wrong_branch") results.back()["folded"] = tip_folded_before_loss(t);
  }
  const int n = static_cast<int>(traces.size());
  return {{"episodes", n},
          {"successes", successes},
          {"success_rate", n ? static_cast<double>(successes) / n : 0.0},
          {"outcomes", outcomes},
          {"results", results}};
}

}  // namespace gw
