// Trajectory JSON: every field round-trips (NaN as null, 64-bit seeds), malformed files
// are named in errors, and writing is all-or-nothing.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "lib/report/atomic_write.hpp"
#include "lib/report/trace_json.hpp"
#include "report_scenes.hpp"

using namespace gw;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool same_number(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

bool same_point(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return same_number(a.x(), b.x()) && same_number(a.y(), b.y()) && same_number(a.z(), b.z());
}

EpisodeTrace rich_trace() {
  EpisodeTrace t = test::box_trace();
  t.anatomy = "coronary_deformed";
  t.controller = "scripted-omega";
  t.target_id = 5;
  t.seed = 18446744073709551557ull;  // largest 64-bit prime: no double can hold it
  t.outcome = "wrong_branch";
  t.detail = "bifurcation 2: entered branch 7 \"left\"";
  t.time_s[3] = 0.1 + 1e-13;  // needs all 17 digits
  t.tip[5] = Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 1.0, -2.5e-7);
  t.action[6] = std::numeric_limits<double>::quiet_NaN();
  t.wire_shapes.insert(t.wire_shapes.begin(), {{0, 0, 0}, {0.5, 1.25, -3}});
  t.wire_shape_frame.insert(t.wire_shape_frame.begin(), 10);
  t.observation_names = {"lambda_t", "omega"};
  for (std::size_t i = 0; i < t.time_s.size(); ++i) {
    t.observation.push_back({1.0 - 0.01 * static_cast<double>(i), -0.5});
    t.goal.push_back(i < 20 ? 0 : 1);
  }
  t.observation[2][1] = std::numeric_limits<double>::quiet_NaN();
  return t;
}

}  // namespace

TEST_CASE("trajectory JSON round-trips every field", "[report][json]") {
  const EpisodeTrace t = rich_trace();
  const std::string dir = test::scratch_dir("json");
  const std::string path = dir + "/episode.json";
  write_trace_json(t, path);
  const EpisodeTrace r = read_trace_json(path);
  CHECK(r.anatomy == t.anatomy);
  CHECK(r.controller == t.controller);
  CHECK(r.target_id == t.target_id);
  CHECK(r.seed == t.seed);
  CHECK(r.outcome == t.outcome);
  CHECK(r.detail == t.detail);
  REQUIRE(r.time_s.size() == t.time_s.size());
  for (std::size_t i = 0; i < t.time_s.size(); ++i) {
    CAPTURE(i);
    CHECK(same_number(r.time_s[i], t.time_s[i]));
    CHECK(same_point(r.tip[i], t.tip[i]));
    CHECK(same_number(r.action[i], t.action[i]));
    CHECK(r.agent_in_control[i] == t.agent_in_control[i]);
  }
  REQUIRE(r.wire_shapes.size() == 2);
  for (std::size_t s = 0; s < 2; ++s) {
    REQUIRE(r.wire_shapes[s].size() == t.wire_shapes[s].size());
    for (std::size_t i = 0; i < t.wire_shapes[s].size(); ++i) CHECK(same_point(r.wire_shapes[s][i], t.wire_shapes[s][i]));
  }
  CHECK(r.wire_shape_frame == t.wire_shape_frame);
  CHECK(r.observation_names == t.observation_names);
  CHECK(r.goal == t.goal);
  REQUIRE(r.observation.size() == t.observation.size());
  for (std::size_t i = 0; i < t.observation.size(); ++i)
    for (std::size_t k = 0; k < 2; ++k) CHECK(same_number(r.observation[i][k], t.observation[i][k]));

  // The file is plain JSON other tools read: schema, null for NaN, columns.
  const auto j = nlohmann::json::parse(slurp(path));
  CHECK(j["schema"] == "guidewire-nav/trajectory/1");
  CHECK(j["units"]["length"] == "mm");
  CHECK(j["num_frames"] == t.time_s.size());
  CHECK(j["frames"]["tip"][5][0].is_null());
  CHECK(j["wire_shapes"][1]["frame"] == 38);
  CHECK(j["observation_names"][1] == "omega");
  CHECK(j["frames"]["observation"][2][1].is_null());
  CHECK(j["frames"]["goal"][25] == 1);
  CHECK(j["wire_shapes"][1]["time_s"].get<double>() == Approx(3.8));
  CHECK_FALSE(fs::exists(path + ".tmp"));
}

TEST_CASE("trajectory JSON: unknown wire-shape frames stay unknown", "[report][json]") {
  EpisodeTrace t = test::box_trace();
  t.wire_shape_frame.clear();
  const EpisodeTrace r = trace_from_json(trace_to_json(t));
  CHECK(r.wire_shape_frame.empty());
  CHECK(r.wire_shapes.size() == 1);
  const auto j = nlohmann::json::parse(trace_to_json(t));
  CHECK(j["wire_shapes"][0]["frame"].is_null());
}

TEST_CASE("trajectory JSON: observations and goals are optional", "[report][json]") {
  const EpisodeTrace t = test::box_trace();
  REQUIRE(t.observation.empty());
  const auto j = nlohmann::json::parse(trace_to_json(t));
  CHECK_FALSE(j["frames"].contains("observation"));
  CHECK_FALSE(j["frames"].contains("goal"));
  const EpisodeTrace r = trace_from_json(trace_to_json(t));
  CHECK(r.observation.empty());
  CHECK(r.goal.empty());
}

TEST_CASE("inconsistent traces are refused with the problem named", "[report][json]") {
  EpisodeTrace t = rich_trace();
  t.observation.pop_back();
  CHECK_THROWS_WITH(check_trace(t), Contains("observation has"));
  t = rich_trace();
  t.observation[4].push_back(0.0);
  CHECK_THROWS_WITH(check_trace(t), Contains("an observation has 3 values but there are 2 observation names"));
  t = rich_trace();
  t.goal.pop_back();
  CHECK_THROWS_WITH(check_trace(t), Contains("goal has"));
  t = test::box_trace();
  t.tip.pop_back();
  CHECK_THROWS_WITH(check_trace(t, "episode 3"), Contains("episode 3") && Contains("tip has 38 frames but time_s has 39"));
  t = test::box_trace();
  t.outcome = "crashed";
  CHECK_THROWS_WITH(check_trace(t), Contains("'crashed'") && Contains("wrong_branch"));
  t = test::box_trace();
  t.wire_shape_frame = {99};
  CHECK_THROWS_WITH(check_trace(t), Contains("wire_shape_frame 99"));
  t.wire_shape_frame = {1, 2};
  CHECK_THROWS_WITH(check_trace(t), Contains("2 entries but there are 1 wire shapes"));
  t = test::box_trace();
  t.target_id = -1;
  CHECK_THROWS_AS(check_trace(t), std::invalid_argument);

  // write_trace_json refuses before creating anything.
  t = test::box_trace();
  t.action.clear();
  const std::string path = test::scratch_dir("json_bad") + "/bad.json";
  CHECK_THROWS_WITH(write_trace_json(t, path), Contains(path) && Contains("action has 0 frames"));
  CHECK_FALSE(fs::exists(path));
}

TEST_CASE("malformed trajectory files are reported with their origin", "[report][json]") {
  CHECK_THROWS_WITH(trace_from_json("{not json", "ep.json"), Contains("ep.json") && Contains("not valid JSON"));
  auto j = nlohmann::json::parse(trace_to_json(test::box_trace()));
  j["schema"] = "guidewire-nav/trajectory/0";
  CHECK_THROWS_WITH(trace_from_json(j.dump(), "ep.json"), Contains("ep.json") && Contains("schema"));
  j = nlohmann::json::parse(trace_to_json(test::box_trace()));
  j.erase("outcome");
  CHECK_THROWS_WITH(trace_from_json(j.dump(), "ep.json"), Contains("missing field 'outcome'"));
  j = nlohmann::json::parse(trace_to_json(test::box_trace()));
  j["frames"]["tip"][0] = {1, 2};
  CHECK_THROWS_WITH(trace_from_json(j.dump(), "ep.json"), Contains("[x, y, z]"));
  j = nlohmann::json::parse(trace_to_json(test::box_trace()));
  j["frames"]["action"].erase(0);
  CHECK_THROWS_WITH(trace_from_json(j.dump(), "ep.json"), Contains("action has 38 frames"));
  CHECK_THROWS_WITH(read_trace_json("/nonexistent/ep.json"), Contains("/nonexistent/ep.json"));
}

TEST_CASE("writing to an unwritable path throws naming it and leaves no partial file", "[report][json]") {
  const std::string dir = test::scratch_dir("json_unwritable");
  const EpisodeTrace t = test::box_trace();

  const std::string missing_dir = dir + "/no/such/dir/episode.json";
  CHECK_THROWS_AS(write_trace_json(t, missing_dir), ReportError);
  CHECK_THROWS_WITH(write_trace_json(t, missing_dir), Contains(missing_dir) && Contains("cannot open for writing"));
  CHECK_FALSE(fs::exists(missing_dir));
  CHECK_FALSE(fs::exists(missing_dir + ".tmp"));

  // Parent is a regular file.
  const std::string file = dir + "/plain_file";
  std::ofstream(file) << "x";
  CHECK_THROWS_AS(write_trace_json(t, file + "/episode.json"), ReportError);
  CHECK_THROWS_WITH(write_trace_json(t, file + "/episode.json"), Contains(file + "/episode.json"));

  // Target is a directory: the temporary file is written, the rename fails, and it is removed.
  const std::string as_dir = dir + "/a_directory";
  fs::create_directories(as_dir);
  CHECK_THROWS_AS(write_trace_json(t, as_dir), ReportError);
  CHECK_THROWS_WITH(write_trace_json(t, as_dir), Contains(as_dir) && Contains("cannot replace"));
  CHECK(fs::is_directory(as_dir));
  CHECK_FALSE(fs::exists(as_dir + ".tmp"));
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"a_directory", "plain_file"});  // nothing else left behind

  CHECK_THROWS_AS(write_file_atomic("", "x"), ReportError);
}

TEST_CASE("rewriting a trajectory replaces the whole file", "[report][json]") {
  const std::string path = test::scratch_dir("json_rewrite") + "/episode.json";
  EpisodeTrace long_trace = rich_trace();
  write_trace_json(long_trace, path);
  const auto long_size = fs::file_size(path);
  EpisodeTrace short_trace = test::box_trace();
  short_trace.time_s.resize(2);
  short_trace.tip.resize(2);
  short_trace.action.resize(2);
  short_trace.agent_in_control.resize(2);
  short_trace.wire_shape_frame = {1};
  write_trace_json(short_trace, path);
  CHECK(fs::file_size(path) < long_size);
  CHECK(read_trace_json(path).time_s.size() == 2);
}
