// evaluate: the paper's results table on our anatomies, each row beside the push-only and
// scripted-omega baselines and the paper's figure. Writes results.md and results.json.
//   evaluate --out results/            # full table (550 episodes a column, 4 columns)
//   evaluate --episode-scale 0.1       # a quick look
//   evaluate --from-json a/results.json b/results.json --out both   # runs on two --seed sets, joined
//   evaluate --out results/ --resume   # after an interruption: the rows results.json holds are kept
//   evaluate --rows coronary-like --episodes 10:10 --out s2   # a shard: episodes 10-19 of the row
// Progress with an ETA goes to stderr; results.json and results.md are rewritten after every row.
#include <algorithm>
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "lib/report/atomic_write.hpp"
#include "base/util/read_json_file.hpp"
#include "lib/runner/controller.hpp"
#include "lib/runner/evaluation_merge.hpp"
#include "lib/runner/evaluation_table.hpp"
#include "lib/runner/procedure_options.hpp"
#include "lib/runner/task_options.hpp"
#include "task/anatomy.hpp"

namespace {

// A results.json an earlier run wrote; throws naming the file when it is unreadable or not one.
nlohmann::json read_results(const std::string& path, const std::string& flag = "--from-json") {
  nlohmann::json result;
  try {
    result = gw::read_json_file(path, "results file");
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(flag + ": " + e.what());
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
// again), in the table's order, so the table grows to the union; pool rows (an anatomy index, gw::index_row)
// come after the table's. A kept row the table no longer has is dropped with a warning.
std::vector<gw::EvaluationRow> rows_to_run(const std::string& rows_filter, const nlohmann::json& kept) {
  std::vector<gw::EvaluationRow> table = gw::paper_table();
  const std::vector<gw::EvaluationRow> selected = gw::select_rows(table, rows_filter);
  auto in_table = [&](const std::string& name) {
    return std::any_of(table.begin(), table.end(), [&](const gw::EvaluationRow& r) { return r.name == name; });
  };
  for (const gw::EvaluationRow& s : selected)
    if (!in_table(s.name)) table.push_back(s);
  for (const nlohmann::json& k : kept) {
    const std::string name = k["name"].get<std::string>();
    if (!in_table(name) && name.rfind("pool ", 0) == 0) table.push_back(gw::index_row(name.substr(5)));
  }
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

// What the command line asks for.
struct EvaluateArgs {
  gw::EvaluationOptions o;
  gw::TaskOptions task;
  gw::ProcedureOptions procedure;  // --reshape-tip, --reshape-tip-length, --step-time-limit
  std::string out_dir = "results", rows_filter, centerlines = "extract", episodes_range;
  std::string controllers = "policy,push-only,scripted-omega,scripted-omega-ccw", planned_seeds = "0";
  std::vector<std::string> from_json;
  bool resume = false, plan = false;
  EvaluateArgs() {
    o.policy = gw::default_policy_path();
    o.base_policy = gw::base_policy_path(o.policy);
    o.index_path = gw::default_anatomy_index();
    o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }
};

void add_evaluate_options(CLI::App& app, EvaluateArgs& a) {
  app.add_option("--policy", a.o.policy, "actor JSON trained on the 4 training anatomies");
  app.add_option("--base-policy", a.o.base_policy,
                 "actor JSON trained on sensitivity/base only (sensitivity rows); give --policy's file to use the "
                 "shipped policy there (noted in the table)");
  app.add_option("--index", a.o.index_path, "anatomy index JSON the table's rows name their anatomies in (default: the repository's anatomies/index.json)");
  app.add_option("--centerlines", a.centerlines, "extract (zero-shot pipeline) | truth");
  app.add_option("--episode-scale", a.o.episode_scale, "multiply every row's episode count");
  app.add_option("--seed", a.o.seed, "episode k of a row uses seed S+k");
  app.add_option("--wire", a.o.wire_path, "guidewire parameter JSON (default: the 0.014\" coronary wire the policies "
                 "were trained with)");
  gw::add_task_options(app, a.task);
  gw::add_procedure_options(app, a.procedure);
  app.add_option("--threads", a.o.threads, "episodes run in parallel");
  app.add_option("--rows", a.rows_filter, "only rows whose name contains one of these comma-separated texts (coronary,var1); "
                 "an anatomy index (POOL/index.json) is a row of its own: every anatomy it lists, 5 episodes each");
  app.add_option("--out", a.out_dir, "folder for results.md and results.json (both rewritten after every row, so an "
                 "interruption loses no finished row)");
  app.add_flag("--resume", a.resume,
               "keep the rows --out's results.json already holds (an interrupted run's, same settings) and run only "
               "the others");
  app.add_option("--reachability-seeds", a.o.reachability_seeds,
                 "probe targets no controller reached with 8 rotation schedules from this many seeds (0 = skip)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--planned-seeds", a.planned_seeds,
                 "plan every target of each row with the procedure planner from up to this many seeds (docs/planning.md; "
                 "0 = skip, the default): the row's \"planned\" figure; 'episodes': plan every episode of the row "
                 "from its own start instead, and each column against those plans");
  app.add_option("--plan-budget", a.o.plan.max_env_steps, "with --planned-seeds: env steps one plan's search may simulate")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--plan-force-limit", a.o.plan.force_limit_N,
                 "with --planned-seeds: the plans' tip-force budget, N")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--controllers", a.controllers,
                 "comma-separated columns: policy, push-only, scripted-omega, scripted-omega-ccw (the scripted "
                 "rule turning the other way)");
  app.add_option("--episodes", a.episodes_range,
                 "FIRST:COUNT: run only episodes FIRST..FIRST+COUNT-1 of each row (a shard, recorded in the "
                 "settings; shards joined with --from-json in episode order are the whole run: "
                 "python -m guidewire_nav.cluster does this on a Ray cluster)");
  app.add_flag("--plan", a.plan,
               "run nothing: print the rows these flags select as JSON ({\"rows\": [{\"name\", \"episodes\"}]}, "
               "episodes before any --episodes shard)");
  app.add_option("--from-json", a.from_json,
                 "run nothing: write results.md (to --out) again from a results.json an earlier run wrote; given "
                 "several (runs on different --seed), join them row by row and write results.json too");
}

// --from-json: results.md again from one results.json, or several runs joined row by row (results.json too).
void from_json(const EvaluateArgs& a) {
  if (a.from_json.size() == 1) {
    // The report's format changes more often than the episodes are worth re-running (43 min).
    write_markdown(read_results(a.from_json[0]), a.out_dir);
    return;
  }
  const std::string merged_path = a.out_dir + "/results.json";
  std::vector<nlohmann::json> runs;
  for (const std::string& path : a.from_json) {
    if (std::filesystem::exists(path) && std::filesystem::exists(merged_path) &&
        std::filesystem::equivalent(path, merged_path))
      throw std::invalid_argument("--from-json: '" + path + "' would be overwritten by the joined table; "
                                  "give another --out");
    runs.push_back(read_results(path));
  }
  const nlohmann::json merged = gw::merge_evaluations(runs, a.from_json);
  std::filesystem::create_directories(a.out_dir);
  gw::write_file_atomic(merged_path, merged.dump(2) + "\n");
  write_markdown(merged, a.out_dir);
}

// --episodes FIRST:COUNT into o.first_episode, o.episode_count; throws naming the flag.
void parse_episode_range(const std::string& text, gw::EvaluationOptions& o) {
  const std::size_t colon = text.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    std::size_t used = 0;
    o.first_episode = std::stoi(text.substr(0, colon), &used);
    if (used != colon) throw std::invalid_argument("first");
    const std::string count = text.substr(colon + 1);
    o.episode_count = std::stoi(count, &used);
    if (used != count.size()) throw std::invalid_argument("count");
  } catch (const std::exception&) {
    throw std::invalid_argument("--episodes must be FIRST:COUNT (two whole numbers), got '" + text + "'");
  }
  if (o.first_episode < 0 || o.episode_count < 1)
    throw std::invalid_argument("--episodes FIRST:COUNT needs FIRST >= 0 and COUNT >= 1, got '" + text + "'");
}

// --planned-seeds N (a whole number >= 0) or 'episodes' into o.planned_seeds, o.planned_per_episode; throws
// naming the flag.
void parse_planned_seeds(const std::string& text, gw::EvaluationOptions& o) {
  o.planned_per_episode = text == "episodes";
  if (o.planned_per_episode) return;
  std::size_t used = 0;
  try {
    o.planned_seeds = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || o.planned_seeds < 0)
    throw std::invalid_argument("--planned-seeds must be a whole number >= 0 or 'episodes', got '" + text + "'");
}

// The evaluation options the flags give, checked.
gw::EvaluationOptions evaluation_options(const EvaluateArgs& a) {
  gw::EvaluationOptions o = a.o;
  o.task = gw::resolve_task_config(a.task);
  o.reshape_tip_per_mm = a.procedure.reshape_tip_per_mm;
  o.reshape_tip_length_mm = a.procedure.reshape_tip_length_mm;
  o.step_time_limit_s = a.procedure.step_time_limit_s;
  if (!a.episodes_range.empty()) parse_episode_range(a.episodes_range, o);
  parse_planned_seeds(a.planned_seeds, o);
  if (a.centerlines != "extract" && a.centerlines != "truth")
    throw std::invalid_argument("--centerlines must be 'extract' or 'truth', got '" + a.centerlines + "'");
  o.extract_centerlines = a.centerlines == "extract";
  o.progress = true;
  o.controllers = gw::split_commas(a.controllers);
  for (const std::string& c : o.controllers)
    if (c != "policy" && c != "push-only" && c != "scripted-omega" && c != "scripted-omega-ccw")
      throw std::invalid_argument("--controllers: unknown controller '" + c +
                                  "' (expected policy, push-only, scripted-omega or scripted-omega-ccw)");
  if (o.controllers.empty()) throw std::invalid_argument("--controllers names no controller");
  if (!std::filesystem::exists(o.base_policy)) o.base_policy.clear();
  return o;
}

// The table: the rows selected (and, with --resume, those kept), results.json and results.md after every row.
void run_table(const EvaluateArgs& a, gw::EvaluationOptions o) {
  const std::string results_path = a.out_dir + "/results.json";
  if (a.resume && std::filesystem::exists(results_path)) {
    o.finished_rows = gw::resumable_rows(read_results(results_path, "--resume"), o);
    std::cerr << "[evaluate] --resume: " << o.finished_rows.size() << " finished row(s) in " << results_path
              << " kept\n";
  } else if (a.resume) {
    std::cerr << "[evaluate] --resume: no " << results_path << " yet, every row runs\n";
  }
  std::filesystem::create_directories(a.out_dir);
  o.on_row = [&](const nlohmann::json& so_far) {  // each finished row at once (atomic: never half a file)
    gw::write_file_atomic(results_path, so_far.dump(2) + "\n");
    write_markdown(so_far, a.out_dir, false);
  };
  const nlohmann::json result = gw::run_evaluation(rows_to_run(a.rows_filter, o.finished_rows), o);
  gw::write_file_atomic(results_path, result.dump(2) + "\n");
  write_markdown(result, a.out_dir);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Reproduce the paper's results table with the shipped policy and two baselines"};
  EvaluateArgs args;
  add_evaluate_options(app, args);
  CLI11_PARSE(app, argc, argv);
  try {
    const gw::EvaluationOptions o = evaluation_options(args);
    if (!args.from_json.empty()) {
      from_json(args);
    } else if (args.plan) {
      nlohmann::json rows = nlohmann::json::array();
      for (const gw::EvaluationRow& row : gw::select_rows(gw::paper_table(), args.rows_filter))
        rows.push_back({{"name", row.name}, {"episodes", gw::scaled_episodes(row, o.episode_scale)}});
      std::cout << nlohmann::json{{"rows", rows}}.dump(2) << "\n";
    } else {
      run_table(args, o);
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
