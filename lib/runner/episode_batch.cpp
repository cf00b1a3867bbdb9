#include "lib/runner/episode_batch.hpp"

#include "lib/runner/episode_force.hpp"

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
  const std::size_t last = static_cast<std::size_t>(strict_end(trace));  // the loss: the strict episode's end
  const double end = trace.time_s[last];
  for (std::size_t f = last + 1; f-- > 0 && end - trace.time_s[f] <= kFoldWindowS;)
    if (trace.observation[f].size() > obs_index::kTheta && trace.observation[f][obs_index::kTheta] < kFoldedTheta)
      return true;
  return false;
}

namespace {

// Whether an episode's force figures (episode_force) keep the tip's peak within 1.5 N; true for a result
// without them (written before forces were recorded).
bool tip_within_limit(const nlohmann::json& force) {
  return !force.contains("peak_tip_N") || force["peak_tip_N"].get<double>() <= kRuptureForceN;
}

// Over the episodes' force figures (episode_force) under `key` of each result (or of its "recovery"):
// {"episodes" with a figure, "mean_peak_node_N", "share_peak_node_over_1_5N", "mean_peak_total_N",
// "share_peak_total_over_1_5N", "mean_peak_tip_N", "share_peak_tip_over_1_5N", "mean_mean_total_N"}, with a force
// limit "mean_push_held_s";
// {} when none has one.
nlohmann::json force_summary(const std::vector<nlohmann::json>& forces) {
  int n = 0, node_over = 0, total_over = 0, tip_over = 0;
  int held_n = 0;
  double node = 0, total = 0, tip = 0, mean = 0, held = 0;
  for (const nlohmann::json& f : forces) {
    if (!f.contains("peak_node_N")) continue;
    ++n;
    if (f.contains("push_held_s")) {
      ++held_n;
      held += f["push_held_s"].get<double>();
    }
    node += f["peak_node_N"].get<double>();
    total += f["peak_total_N"].get<double>();
    tip += f["peak_tip_N"].get<double>();
    mean += f["mean_total_N"].get<double>();
    node_over += f["peak_node_N"].get<double>() > kRuptureForceN;
    total_over += f["peak_total_N"].get<double>() > kRuptureForceN;
    tip_over += f["peak_tip_N"].get<double>() > kRuptureForceN;
  }
  if (n == 0) return nlohmann::json::object();
  nlohmann::json out = {{"episodes", n},
                        {"mean_peak_node_N", node / n},
                        {"share_peak_node_over_1_5N", static_cast<double>(node_over) / n},
                        {"mean_peak_total_N", total / n},
                        {"share_peak_total_over_1_5N", static_cast<double>(total_over) / n},
                        {"mean_peak_tip_N", tip / n},
                        {"share_peak_tip_over_1_5N", static_cast<double>(tip_over) / n},
                        {"mean_mean_total_N", mean / n}};
  if (held_n > 0) out["mean_push_held_s"] = held / held_n;
  return out;
}

// Over the frames of two passes: the largest peaks, and the mean total weighted by the env steps of each.
nlohmann::json joined_force(const nlohmann::json& a, int a_steps, const nlohmann::json& b, int b_steps) {
  if (a.empty() || b.empty()) return a.empty() ? b : a;
  nlohmann::json f;
  for (const char* k : {"peak_node_N", "peak_total_N", "peak_tip_N"}) f[k] = std::max(a[k].get<double>(), b[k].get<double>());
  const int n = std::max(1, a_steps + b_steps);
  f["mean_total_N"] = (a["mean_total_N"].get<double>() * a_steps + b["mean_total_N"].get<double>() * b_steps) / n;
  if (a.contains("push_held_s") && b.contains("push_held_s"))
    f["push_held_s"] = a["push_held_s"].get<double>() + b["push_held_s"].get<double>();
  return f;
}

// A result's "reshape" entry: the whole procedure, the reshaped second pass included when there was one.
nlohmann::json reshape_result(const EpisodeTrace& t) {
  const int first_steps = static_cast<int>(t.time_s.size()) - 1;
  const double first_time = t.time_s.empty() ? 0.0 : t.time_s.back();
  nlohmann::json r = {{"tip_curvature_per_mm", t.reshape_tip_per_mm},
                      {"tip_length_mm", t.reshape_tip_length_mm},
                      {"reshaped", !t.reshaped.empty()},
                      {"outcome", procedure_outcome(t)},
                      {"detail", procedure_detail(t)},
                      {"attempts", t.recovery_attempts_used},
                      {"steps", first_steps},
                      {"procedure_time_s", first_time}};
  nlohmann::json force = episode_force(t, 0, first_steps);
  if (!t.reshaped.empty()) {
    const EpisodeTrace& second = t.reshaped.front();
    const int second_steps = static_cast<int>(second.time_s.size()) - 1;
    r["outcome"] = procedure_outcome(second);
    r["detail"] = procedure_detail(second);
    r["attempts"] = t.recovery_attempts_used + second.recovery_attempts_used;
    r["steps"] = first_steps + second_steps;
    r["withdrawal_s"] = t.reshape_withdrawal_s;
    r["procedure_time_s"] = first_time + t.reshape_withdrawal_s + (second.time_s.empty() ? 0.0 : second.time_s.back());
    force = joined_force(force, first_steps, episode_force(second, 0, second_steps), second_steps);
  }
  if (!force.empty()) r["force"] = force;
  return r;
}

}  // namespace

nlohmann::json summarize_results(const nlohmann::json& results) {
  nlohmann::json outcomes = nlohmann::json::object(), recovered_outcomes = nlohmann::json::object();
  for (const std::string& o : kTraceOutcomes) outcomes[o] = recovered_outcomes[o] = 0;
  std::vector<nlohmann::json> forces, recovered_forces;
  int successes = 0, recovered = 0, with_recovery = 0, attempts_allowed = 0, attempts = 0;
  int safe_successes = 0, safe_recovered = 0;  // ... whose peak tip force stayed within 1.5 N (issue 64's figures)
  double procedure_time = 0;
  nlohmann::json reshape_outcomes = nlohmann::json::object();
  for (const std::string& o : kTraceOutcomes) reshape_outcomes[o] = 0;
  std::vector<nlohmann::json> reshape_forces;
  int with_reshape = 0, reshape_successes = 0, reshaped = 0;
  double reshape_time = 0, reshape_curvature = 0, reshape_length = 0;
  for (const nlohmann::json& ep : results) {
    const std::string outcome = ep.at("outcome").get<std::string>();
    successes += outcome == "success";
    safe_successes += outcome == "success" && tip_within_limit(ep.value("force", nlohmann::json::object()));
    outcomes[outcome] = outcomes.value(outcome, 0) + 1;
    forces.push_back(ep.value("force", nlohmann::json::object()));
    if (ep.contains("recovery")) {
      const nlohmann::json& r = ep["recovery"];
      ++with_recovery;
      attempts_allowed = std::max(attempts_allowed, r.at("attempts_allowed").get<int>());
      recovered += r.at("outcome") == "success";
      safe_recovered += r.at("outcome") == "success" && tip_within_limit(r.value("force", nlohmann::json::object()));
      recovered_outcomes[r.at("outcome").get<std::string>()] = recovered_outcomes.value(r.at("outcome").get<std::string>(), 0) + 1;
      attempts += r.at("attempts").get<int>();
      procedure_time += r.at("procedure_time_s").get<double>();
      recovered_forces.push_back(r.value("force", nlohmann::json::object()));
    }
    if (ep.contains("reshape")) {
      const nlohmann::json& r = ep["reshape"];
      ++with_reshape;
      reshape_curvature = r.at("tip_curvature_per_mm").get<double>();
      reshape_length = r.value("tip_length_mm", 0.0);  // 0: a result written before the length was recorded
      reshape_successes += r.at("outcome") == "success";
      reshaped += r.at("reshaped").get<bool>();
      const std::string o = r.at("outcome").get<std::string>();
      reshape_outcomes[o] = reshape_outcomes.value(o, 0) + 1;
      reshape_time += r.at("procedure_time_s").get<double>();
      reshape_forces.push_back(r.value("force", nlohmann::json::object()));
    }
  }
  const int n = static_cast<int>(results.size());
  nlohmann::json out = {{"episodes", n},
                        {"successes", successes},
                        {"success_rate", n ? static_cast<double>(successes) / n : 0.0},
                        {"successes_tip_within_1_5N", safe_successes},
                        {"outcomes", outcomes},
                        {"results", results}};
  const nlohmann::json force = force_summary(forces);
  if (!force.empty()) out["force"] = force;
  if (with_recovery > 0) {
    out["recovery"] = {{"attempts_allowed", attempts_allowed},
                       {"episodes", with_recovery},
                       {"successes", recovered},
                       {"success_rate", static_cast<double>(recovered) / with_recovery},
                       {"successes_tip_within_1_5N", safe_recovered},
                       {"outcomes", recovered_outcomes},
                       {"mean_attempts", static_cast<double>(attempts) / with_recovery},
                       {"mean_procedure_time_s", procedure_time / with_recovery}};
    const nlohmann::json rf = force_summary(recovered_forces);
    if (!rf.empty()) out["recovery"]["force"] = rf;
  }
  if (with_reshape > 0) {
    out["reshape"] = {{"tip_curvature_per_mm", reshape_curvature},
                      {"episodes", with_reshape},
                      {"successes", reshape_successes},
                      {"success_rate", static_cast<double>(reshape_successes) / with_reshape},
                      {"outcomes", reshape_outcomes},
                      {"reshaped", reshaped},
                      {"mean_procedure_time_s", reshape_time / with_reshape}};
    if (reshape_length > 0) out["reshape"]["tip_length_mm"] = reshape_length;
    const nlohmann::json sf = force_summary(reshape_forces);
    if (!sf.empty()) out["reshape"]["force"] = sf;
  }
  return out;
}

nlohmann::json summarize_episodes(const std::vector<EpisodeTrace>& traces) {
  nlohmann::json results = nlohmann::json::array();
  for (const EpisodeTrace& t : traces) {
    const int end = strict_end(t);
    results.push_back({{"anatomy", t.anatomy},
                       {"controller", t.controller},
                       {"target", t.target_id},
                       {"seed", t.seed},
                       {"outcome", t.outcome},
                       {"detail", t.detail},
                       {"steps", end},
                       {"sim_time_s", t.time_s.empty() ? 0.0 : t.time_s[static_cast<std::size_t>(end)]}});
    if (!std::isnan(t.omega_at_loss)) results.back()["omega_at_loss"] = t.omega_at_loss;
    if (t.outcome == "wrong_branch") results.back()["folded"] = tip_folded_before_loss(t);
    const nlohmann::json force = episode_force(t, 0, end);
    if (!force.empty()) results.back()["force"] = force;
    if (t.recovery_attempts_allowed > 0) {
      // The whole procedure: the strict episode and what recovery did after it.
      const int last = static_cast<int>(t.time_s.size()) - 1;
      const nlohmann::json whole = episode_force(t, 0, last);
      nlohmann::json r = {{"attempts_allowed", t.recovery_attempts_allowed},
                          {"attempts", t.recovery_attempts_used},
                          {"outcome", t.recovery_outcome},
                          {"detail", t.recovery_detail},
                          {"steps", last},
                          {"procedure_time_s", t.time_s.empty() ? 0.0 : t.time_s.back()}};
      if (!whole.empty()) r["force"] = whole;
      results.back()["recovery"] = r;
    }
    if (t.reshape_tip_per_mm > 0) results.back()["reshape"] = reshape_result(t);
  }
  return summarize_results(results);
}

}  // namespace gw
