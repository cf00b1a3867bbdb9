#include "lib/runner/evaluation_merge.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "lib/runner/episode_batch.hpp"
#include "lib/runner/evaluation_table.hpp"
#include "lib/runner/row_planned.hpp"

namespace gw {
namespace {

const nlohmann::json* find_row(const nlohmann::json& run, const std::string& name) {
  for (const nlohmann::json& r : run["rows"])
    if (r.value("name", "") == name) return &r;
  return nullptr;
}

// One column's summaries (summarize_episodes) of the same row in several runs, as one: the episodes
// concatenated in run order and summarized again (counts, outcomes, force and recovery figures).
nlohmann::json merge_summaries(const std::vector<const nlohmann::json*>& parts) {
  nlohmann::json results = nlohmann::json::array();
  for (const nlohmann::json* s : parts)
    for (const nlohmann::json& ep : s->at("results")) results.push_back(ep);
  return summarize_results(results);
}

// The ceilings of a row's runs added up; absent when a run did not measure it.
std::optional<nlohmann::json> merge_ceilings(const std::vector<const nlohmann::json*>& rows) {
  nlohmann::json out = {{"episodes", 0}, {"reached", 0}, {"reached_by_a_controller", 0},
                        {"reached_only_by_a_schedule", nlohmann::json::array()},
                        {"reached_by_none", nlohmann::json::array()}};
  for (const nlohmann::json* r : rows) {
    if (!r->contains("ceiling")) return std::nullopt;
    const nlohmann::json& c = r->at("ceiling");
    for (const char* count : {"episodes", "reached", "reached_by_a_controller"})
      out[count] = out[count].get<int>() + c.at(count).get<int>();
    for (const char* list : {"reached_only_by_a_schedule", "reached_by_none"})
      for (const nlohmann::json& ep : c.at(list)) out[list].push_back(ep);
  }
  // In episode_key order, as one run lists them (row_ceiling), whatever the order of the runs.
  for (const char* list : {"reached_only_by_a_schedule", "reached_by_none"})
    std::stable_sort(out[list].begin(), out[list].end(),
                     [](const nlohmann::json& a, const nlohmann::json& b) { return episode_key(a) < episode_key(b); });
  return out;
}

// Targets no column reached in the merged row: a run's verdict on a target another run's controllers
// reached no longer applies; two runs' verdicts on the same target combine (reachable if either says so).
nlohmann::json merge_reachability(const std::vector<const nlohmann::json*>& rows, const nlohmann::json& results) {
  std::set<std::string> reached;
  for (const auto& [column, summary] : results.items())
    for (const nlohmann::json& ep : summary["results"])
      if (ep.value("outcome", "") == "success")
        reached.insert(target_key(ep["anatomy"].get<std::string>(), ep["target"].get<int>()));
  std::map<std::string, nlohmann::json> verdicts;
  for (const nlohmann::json* r : rows)
    for (const nlohmann::json& t : r->value("reachability", nlohmann::json::array())) {
      const std::string key = t.value("key", "");
      if (reached.count(key)) continue;
      auto [it, fresh] = verdicts.emplace(key, t);
      if (!fresh && !it->second.value("reachable", false) && t.value("reachable", false)) it->second = t;
    }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [key, t] : verdicts) out.push_back(t);
  return out;
}

// The row's "planned" figure over its runs: per episode (each shard planned its own episodes) joined and read
// against the merged columns; per target (every run plans every target) the first run's; absent when a run lacks it.
std::optional<nlohmann::json> merge_planned(const std::vector<const nlohmann::json*>& rows,
                                            const nlohmann::json& results) {
  std::vector<const nlohmann::json*> parts;
  for (const nlohmann::json* r : rows) {
    if (!r->contains("planned")) return std::nullopt;
    parts.push_back(&r->at("planned"));
  }
  if (!parts[0]->contains("per_episode")) return *parts[0];
  nlohmann::json joined = join_episodes_planned(parts);
  joined["columns"] = planned_against_columns(joined, results);
  return joined;
}

using RunName = std::function<std::string(std::size_t)>;

// The columns of one row over its runs; refuses a column one run lacks and an episode two runs share.
nlohmann::json merge_columns(const std::vector<const nlohmann::json*>& parts, const std::string& row,
                             const RunName& name_of) {
  const nlohmann::json& first = parts[0]->at("results");
  for (std::size_t i = 1; i < parts.size(); ++i)
    for (const auto& [column, unused] : parts[i]->at("results").items())
      if (!first.contains(column))
        throw std::invalid_argument("merge: row '" + row + "' has columns in " + name_of(i) + " that " +
                                    name_of(0) + " lacks");
  nlohmann::json merged = nlohmann::json::object();
  for (const auto& [column, unused] : first.items()) {
    std::vector<const nlohmann::json*> summaries;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (!parts[i]->at("results").contains(column))
        throw std::invalid_argument("merge: row '" + row + "' has no column '" + column + "' in " + name_of(i));
      summaries.push_back(&parts[i]->at("results").at(column));
    }
    std::set<std::string> seen;
    for (const nlohmann::json* s : summaries)
      for (const nlohmann::json& ep : s->at("results"))
        if (!seen.insert(episode_key(ep)).second)
          throw std::invalid_argument("merge: row '" + row + "', column '" + column + "': episode " +
                                      episode_key(ep) + " is in two runs (the same --seed twice?)");
    merged[column] = merge_summaries(summaries);
  }
  return merged;
}

// One row over its runs (parts[i] is the row in run i).
nlohmann::json merge_row(const std::vector<const nlohmann::json*>& parts, const std::string& row,
                         const RunName& name_of) {
  nlohmann::json merged = *parts[0];
  merged["paper_episodes"] = paper_episodes(merged);
  merged["episodes"] = 0;
  merged["wall_time_s"] = 0.0;
  merged["notes"] = nlohmann::json::array();
  std::set<std::string> notes, skipped;
  for (const nlohmann::json* r : parts) {
    merged["episodes"] = merged["episodes"].get<int>() + r->value("episodes", 0);
    merged["wall_time_s"] = merged["wall_time_s"].get<double>() + r->value("wall_time_s", 0.0);
    for (const nlohmann::json& n : r->value("notes", nlohmann::json::array()))
      if (notes.insert(n.get<std::string>()).second) merged["notes"].push_back(n);
    if (r->contains("skipped")) skipped.insert(r->at("skipped").get<std::string>());
  }
  merged.erase("ceiling");
  merged.erase("planned");
  if (!skipped.empty()) {  // a row skipped in one run has no episodes there to pair
    std::string why;
    for (const std::string& s : skipped) why += (why.empty() ? "" : "; ") + s;
    merged["skipped"] = why;
    merged["results"] = nlohmann::json::object();
    merged["reachability"] = nlohmann::json::array();
    return merged;
  }
  merged["results"] = merge_columns(parts, row, name_of);
  merged["reachability"] = merge_reachability(parts, merged["results"]);
  if (std::optional<nlohmann::json> ceiling = merge_ceilings(parts)) merged["ceiling"] = *ceiling;
  if (std::optional<nlohmann::json> planned = merge_planned(parts, merged["results"])) merged["planned"] = *planned;
  return merged;
}

}  // namespace

nlohmann::json merge_evaluations(const std::vector<nlohmann::json>& runs, const std::vector<std::string>& names) {
  if (runs.empty()) throw std::invalid_argument("merge: no results to merge");
  const RunName name_of = [&](std::size_t i) { return i < names.size() ? names[i] : "run " + std::to_string(i + 1); };
  const nlohmann::json settings0 = run_task_settings(runs[0]);
  for (std::size_t i = 1; i < runs.size(); ++i) {
    const nlohmann::json settings = run_task_settings(runs[i]);  // named: items() of a temporary would dangle
    for (const auto& [key, value] : settings.items())
      if (value != settings0[key])
        throw std::invalid_argument("merge: " + name_of(i) + " ran with " + key + " " + value.dump() + ", " +
                                    name_of(0) + " with " + settings0[key].dump() + ": different experiments");
  }
  for (std::size_t i = 1; i < runs.size(); ++i)  // rows only a later run has would vanish silently
    for (const nlohmann::json& r : runs[i]["rows"])
      if (!find_row(runs[0], r.value("name", "")))
        throw std::invalid_argument("merge: row '" + r.value("name", "") + "' is in " + name_of(i) +
                                    " but not in " + name_of(0));
  nlohmann::json out_rows = nlohmann::json::array();
  for (const nlohmann::json& first : runs[0]["rows"]) {
    const std::string row = first.value("name", "");
    std::vector<const nlohmann::json*> parts;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const nlohmann::json* r = find_row(runs[i], row);
      if (!r) throw std::invalid_argument("merge: row '" + row + "' is in " + name_of(0) + " but not in " + name_of(i));
      // paper_episodes() falls back to the paper's table for runs written before rows recorded it
      if (r->value("paper", -1.0) != first.value("paper", -1.0) || paper_episodes(*r) != paper_episodes(first))
        throw std::invalid_argument("merge: row '" + row + "' has a different paper figure in " + name_of(i));
      parts.push_back(r);
    }
    out_rows.push_back(merge_row(parts, row, name_of));
  }
  // Shards of one run (evaluate --episodes, settings alike but for the range): joined, they are that run.
  bool shards = true;
  nlohmann::json whole = runs[0].value("settings", nlohmann::json::object());
  whole.erase("episodes");
  for (const nlohmann::json& r : runs) {
    nlohmann::json s = r.value("settings", nlohmann::json::object());
    shards = shards && s.contains("episodes") && s.erase("episodes") && s == whole;
  }
  if (shards) return {{"rows", out_rows}, {"settings", whole}};
  nlohmann::json settings = nlohmann::json::array();
  for (std::size_t i = 0; i < runs.size(); ++i)
    settings.push_back({{"run", name_of(i)}, {"settings", runs[i].value("settings", nlohmann::json::object())}});
  return {{"rows", out_rows}, {"settings", {{"merged_from", settings}}}};
}

}  // namespace gw
