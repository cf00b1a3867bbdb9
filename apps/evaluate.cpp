// evaluate: the paper's results table on our anatomies, each row beside the push-only and
// scripted-omega baselines and the paper's figure. Writes results.md and results.json.
//   evaluate --out results/            # full table (550 episodes a column, 4 columns)
//   evaluate --episode-scale 0.1       # a quick look
//   evaluate --from-json a/results.json b/results.json --out both   # runs on two --seed sets, joined
//   evaluate --out results/ --resume   # after an interruption: the rows results.json holds are kept
//   evaluate --rows coronary-like --episodes 10:10 --out s2   # a shard: episodes 10-19 of the row
// Progress with an ETA goes to stderr; results.json and results.md are rewritten after every row.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "apps/report/atomic_write.hpp"
#include "apps/runner/controller.hpp"
#include "apps/runner/evaluation_merge.hpp"
#include "apps/runner/evaluation_table.hpp"
#include "apps/runner/task_options.hpp"
#include "engine/task/anatomy.hpp"

namespace {

// A results.json an earlier run wrote; throws naming the file when it is unreadable or not one.
nlohmann::json read_results(const std::string& path, const std::string& flag = "--from-json") {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(flag + ": cannot read '" + path + "'");
  nlohmann::json result;
  try {
    result = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(flag + ": '" + path + "' is not JSON: " + e.what());
  }
  if (!result.contains("rows") || !result["rows"].is_array())
    throw std::runtime_error(flag + ": '" + path + "' has no \"rows\" array (not an evaluate results.json)");
  return result;
}

// results.md in `out_dir`, and the same table on stdout.
void write_markdown(const nlohmann::json& result, const std::string& out_dir, bool print = true) {
  const std::string md = gw::evaluation_to_markdown(result);
  std::filesystem::create_directories(out_dir);
  gw::write_file_atomic(out_dir + "/results.md", md);
  if (print) std::cout << md;
}

// The rows to run: those --rows selects and, resuming, those the earlier run finished (kept, not run
// again), in the table's order, so the table grows to the union. A kept row the table no longer has is
// dropped with a warning.
std::vector<gw::EvaluationRow> rows_to_run(const std::string& rows_filter, const nlohmann::json& kept) {
  const std::vector<gw::EvaluationRow> table = gw::paper_table(), selected = gw::select_rows(table, rows_filter);
  std::vector<gw::EvaluationRow> out;
  for (const gw::EvaluationRow& row : table) {
    bool use = false;
    for (const gw::EvaluationRow& s : selected) use = use || s.name == row.name;
    for (const nlohmann::json& k : kept) use = use || k["name"] == row.name;
    if (use) out.push_back(row);
  }
  for (const nlohmann::json& k : kept) {
    bool known = false;
    for (const gw::EvaluationRow& row : table) known = known || k["name"] == row.name;
    if (!known) std::cerr << "[evaluate] --resume: row '" << k["name"].get<std::string>() << "' is no longer in the table: dropped\n";
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Reproduce the paper's results table with the shipped policy and two baselines"};
  gw::EvaluationOptions o;
  o.policy = gw::default_policy_path();
  o.base_policy = gw::base_policy_path(o.policy);
  o.index_path = gw::default_anatomy_index();
  o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string out_dir = "results", rows_filter, centerlines = "extract";
  app.add_option("--policy", o.policy, "actor JSON trained on the 4 training anatomies");
  app.add_option("--base-policy", o.base_policy,
                 "actor JSON trained on sensitivity/base only (sensitivity rows); give --policy's file to use the "
                 "shipped policy there (noted in the table)");
  app.add_option("--index", o.index_path, "anatomy index JSON the table's rows name their anatomies in (default: the repository's anatomies/index.json)");
  app.add_option("--centerlines", centerlines, "extract (zero-shot pipeline) | truth");
  app.add_option("--episode-scale", o.episode_scale, "multiply every row's episode count");
  app.add_option("--seed", o.seed, "episode k of a row uses seed S+k");
  app.add_option("--wire", o.wire_path, "guidewire parameter JSON (default: the 0.014\" coronary wire the policies "
                 "were trained with)");
  gw::TaskOptions task_options;
  gw::add_task_options(app, task_options);
  CLI::Option* reshape_option = app.add_option("--reshape-tip", o.reshape_tip_per_mm,
                 "when a procedure does not reach the target (with --recovery: after its pull-backs), withdraw the wire, "
                 "reshape its tip to this curvature (1/mm; the wire's own is 0.2) and navigate again from the inlet "
                 "(docs/recovery.md); the \"with reshape\" figures. 0 = never")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--reshape-tip-length", o.reshape_tip_length_mm,
                 "with --reshape-tip: the reshaped tip's length, mm (the bent, softer distal part; the wire's own is 6). "
                 "0 = the wire's own")
      ->check(CLI::NonNegativeNumber)
      ->needs(reshape_option);
  app.add_option("--step-time-limit", o.step_time_limit_s, "end an episode as a timeout when one env step runs longer than this many seconds of wall time (0 = no limit, the default: with a limit an outcome can depend on the machine's load; for surfaces where the contact solver crawls)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--threads", o.threads, "episodes run in parallel");
  app.add_option("--rows", rows_filter, "only rows whose name contains one of these comma-separated texts (coronary,var1)");
  app.add_option("--out", out_dir, "folder for results.md and results.json (both rewritten after every row, so an "
                 "interruption loses no finished row)");
  bool resume = false;
  app.add_flag("--resume", resume,
               "keep the rows --out's results.json already holds (an interrupted run's, same settings) and run only "
               "the others");
  std::string controllers = "policy,push-only,scripted-omega,scripted-omega-ccw";
  app.add_option("--reachability-seeds", o.reachability_seeds,
                 "probe targets no controller reached with 8 rotation schedules from this many seeds (0 = skip)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--controllers", controllers,
                 "comma-separated columns: policy, push-only, scripted-omega, scripted-omega-ccw (the scripted "
                 "rule turning the other way)");
  std::string episodes_range;
  app.add_option("--episodes", episodes_range,
                 "FIRST:COUNT: run only episodes FIRST..FIRST+COUNT-1 of each row (a shard, recorded in the "
                 "settings; shards joined with --from-json in episode order are the whole run: "
                 "python -m guidewire_nav.cluster does this on a Ray cluster)");
  bool plan = false;
  app.add_flag("--plan", plan,
               "run nothing: print the rows these flags select as JSON ({\"rows\": [{\"name\", \"episodes\"}]}, "
               "episodes before any --episodes shard)");
  std::vector<std::string> from_json;
  app.add_option("--from-json", from_json,
                 "run nothing: write results.md (to --out) again from a results.json an earlier run wrote; given "
                 "several (runs on different --seed), join them row by row and write results.json too");
  CLI11_PARSE(app, argc, argv);
  try {
    o.task = gw::resolve_task_config(task_options);
    if (from_json.size() == 1) {
      // The report's format changes more often than the episodes are worth re-running (43 min).
      write_markdown(read_results(from_json[0]), out_dir);
      return 0;
    }
    if (from_json.size() > 1) {
      const std::string merged_path = out_dir + "/results.json";
      std::vector<nlohmann::json> runs;
      for (const std::string& path : from_json) {
        if (std::filesystem::exists(path) && std::filesystem::exists(merged_path) &&
            std::filesystem::equivalent(path, merged_path))
          throw std::invalid_argument("--from-json: '" + path + "' would be overwritten by the joined table; "
                                      "give another --out");
        runs.push_back(read_results(path));
      }
      const nlohmann::json merged = gw::merge_evaluations(runs, from_json);
      std::filesystem::create_directories(out_dir);
      gw::write_file_atomic(merged_path, merged.dump(2) + "\n");
      write_markdown(merged, out_dir);
      return 0;
    }
    if (plan) {
      nlohmann::json rows = nlohmann::json::array();
      for (const gw::EvaluationRow& row : gw::select_rows(gw::paper_table(), rows_filter))
        rows.push_back({{"name", row.name}, {"episodes", gw::scaled_episodes(row, o.episode_scale)}});
      std::cout << nlohmann::json{{"rows", rows}}.dump(2) << "\n";
      return 0;
    }
    if (!episodes_range.empty()) {
      const std::size_t colon = episodes_range.find(':');
      try {
        if (colon == std::string::npos) throw std::invalid_argument("no colon");
        std::size_t used = 0;
        o.first_episode = std::stoi(episodes_range.substr(0, colon), &used);
        if (used != colon) throw std::invalid_argument("first");
        const std::string count = episodes_range.substr(colon + 1);
        o.episode_count = std::stoi(count, &used);
        if (used != count.size()) throw std::invalid_argument("count");
      } catch (const std::exception&) {
        throw std::invalid_argument("--episodes must be FIRST:COUNT (two whole numbers), got '" + episodes_range + "'");
      }
      if (o.first_episode < 0 || o.episode_count < 1)
        throw std::invalid_argument("--episodes FIRST:COUNT needs FIRST >= 0 and COUNT >= 1, got '" + episodes_range + "'");
    }
    if (centerlines != "extract" && centerlines != "truth")
      throw std::invalid_argument("--centerlines must be 'extract' or 'truth', got '" + centerlines + "'");
    o.extract_centerlines = centerlines == "extract";
    o.progress = true;
    o.controllers = gw::split_commas(controllers);
    for (const std::string& c : o.controllers)
      if (c != "policy" && c != "push-only" && c != "scripted-omega" && c != "scripted-omega-ccw")
        throw std::invalid_argument("--controllers: unknown controller '" + c +
                                    "' (expected policy, push-only, scripted-omega or scripted-omega-ccw)");
    if (o.controllers.empty()) throw std::invalid_argument("--controllers names no controller");
    if (!std::filesystem::exists(o.base_policy)) o.base_policy.clear();
    const std::string results_path = out_dir + "/results.json";
    if (resume && std::filesystem::exists(results_path)) {
      o.finished_rows = gw::resumable_rows(read_results(results_path, "--resume"), o);
      std::cerr << "[evaluate] --resume: " << o.finished_rows.size() << " finished row(s) in " << results_path
                << " kept\n";
    } else if (resume) {
      std::cerr << "[evaluate] --resume: no " << results_path << " yet, every row runs\n";
    }
    std::filesystem::create_directories(out_dir);
    o.on_row = [&](const nlohmann::json& so_far) {  // each finished row at once (atomic: never half a file)
      gw::write_file_atomic(results_path, so_far.dump(2) + "\n");
      write_markdown(so_far, out_dir, false);
    };
    const nlohmann::json result = gw::run_evaluation(rows_to_run(rows_filter, o.finished_rows), o);
    gw::write_file_atomic(results_path, result.dump(2) + "\n");
    write_markdown(result, out_dir);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
