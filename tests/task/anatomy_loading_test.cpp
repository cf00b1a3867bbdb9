// Loading anatomies: the index (sets, names), explicit paths, and every way it can go wrong.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "task/anatomy.hpp"
#include "task/episode.hpp"
#include "task/navigation_task.hpp"

namespace fs = std::filesystem;

namespace {
const std::string kIndex = std::string(GW_SOURCE_DIR) + "/anatomies/index.json";
const std::string kT1 = std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y";

fs::path scratch_dir(const std::string& name) {
  const fs::path d = fs::path(GW_BINARY_DIR) / "test_task_scratch" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST_CASE("anatomy sources: set names, anatomy names and paths resolve", "[task][anatomy]") {
  const auto train = gw::resolve_anatomy_sources("train", kIndex);
  REQUIRE(train.size() == 4);
  CHECK(train[0].name == "t1_straight_y");
  for (const auto& s : train) {
    CHECK(fs::exists(s.mesh));
    CHECK(fs::exists(s.truth));
  }
  const auto two = gw::resolve_anatomy_sources(" t4_s_curving_back , t1_straight_y", kIndex);
  REQUIRE(two.size() == 2);
  CHECK(two[0].name == "t4_s_curving_back");
  const auto by_mesh = gw::resolve_anatomy_sources(kT1 + ".stl", "/nonexistent/index.json");  // index not needed
  REQUIRE(by_mesh.size() == 1);
  CHECK(by_mesh[0].name == "t1_straight_y");
  CHECK(by_mesh[0].truth == kT1 + ".truth.json");
  const auto by_truth = gw::resolve_anatomy_sources(kT1 + ".truth.json", kIndex);
  CHECK(by_truth[0].mesh == kT1 + ".stl");
  CHECK(gw::default_anatomy_index() == kIndex);
  // another index's path (a generated pool): every anatomy it lists, its paths relative to its folder's parent
  const fs::path d = scratch_dir("pool_index");
  fs::create_directories(d / "pool" / "a");
  fs::copy_file(kT1 + ".stl", d / "pool" / "a" / "one.stl");
  fs::copy_file(kT1 + ".truth.json", d / "pool" / "a" / "one.truth.json");
  std::ofstream(d / "pool" / "index.json")
      << R"({"anatomies": [{"name": "one", "set": "a", "mesh": "pool/a/one.stl", "truth": "pool/a/one.truth.json"}]})";
  const auto pool = gw::resolve_anatomy_sources("t1_straight_y," + (d / "pool" / "index.json").string(), kIndex);
  REQUIRE(pool.size() == 2);
  CHECK(pool[1].name == "one");
  CHECK(fs::exists(pool[1].mesh));
  CHECK(fs::exists(pool[1].truth));
  CHECK_THROWS_WITH(gw::resolve_anatomy_sources((d / "missing.json").string(), kIndex),
                    Catch::Contains("missing.json") && Catch::Contains("does not exist"));
}

TEST_CASE("anatomy sources: clear errors", "[task][anatomy]") {
  CHECK_THROWS_WITH(gw::resolve_anatomy_sources("", kIndex), Catch::Contains("empty"));
  CHECK_THROWS_WITH(gw::resolve_anatomy_sources("t9_nothing", kIndex),
                    Catch::Contains("'t9_nothing'") && Catch::Contains("index.json"));
  CHECK_THROWS_WITH(gw::resolve_anatomy_sources("train", "/nonexistent/index.json"),
                    Catch::Contains("/nonexistent/index.json"));
  CHECK_THROWS_WITH(gw::resolve_anatomy_sources("/nonexistent/v.stl", kIndex), Catch::Contains("/nonexistent/v.stl"));
  const fs::path d = scratch_dir("no_truth");
  fs::copy_file(kT1 + ".stl", d / "lonely.stl");
  CHECK_THROWS_WITH(gw::resolve_anatomy_sources((d / "lonely.stl").string(), kIndex),
                    Catch::Contains("lonely.truth.json"));
  std::ofstream(d / "index.json") << "{ not json";
  CHECK_THROWS_WITH(gw::resolve_anatomy_sources("train", (d / "index.json").string()), Catch::Contains("not valid JSON"));
  std::ofstream(d / "no_mesh.json") << R"({"anatomies": [{"name": "x", "set": "train", "truth": "x.truth.json"}]})";
  CHECK_THROWS_WITH(gw::resolve_anatomy_sources("train", (d / "no_mesh.json").string()),
                    Catch::Contains("no_mesh.json") && Catch::Contains("bad anatomy entry") && Catch::Contains("mesh"));
  std::ofstream(d / "bad.truth.json") << R"({"schema":"guidewire-nav/centerline/1"})";
  fs::copy_file(kT1 + ".stl", d / "bad.stl");
  CHECK_THROWS_WITH(gw::load_anatomies((d / "bad.stl").string(), kIndex), Catch::Contains("bad.truth.json"));
}

TEST_CASE("anatomy: a training anatomy loads with its scene and branch polylines", "[task][anatomy]") {
  const gw::Anatomy a = gw::load_anatomy("t1", kT1 + ".stl", kT1 + ".truth.json");
  CHECK(a.scene != nullptr);
  CHECK(a.graph.targets.size() == 2);
  CHECK(a.branch_lines.size() == a.graph.branches.size());
  CHECK(a.mesh_path == kT1 + ".stl");
  gw::CenterlineGraph empty = a.graph;
  empty.targets.clear();
  CHECK_THROWS_WITH(gw::make_anatomy("e", empty, nullptr), Catch::Contains("no targets"));
}

TEST_CASE("anatomy sources: an index entry's wire is the wire that anatomy is navigated with", "[task][anatomy]") {
  // A pool mixing anatomies of two wires (an arch pool names the aortic wire): one task, one wire model each.
  const fs::path d = scratch_dir("wire_index");
  fs::create_directories(d / "pool" / "a");
  fs::copy_file(kT1 + ".stl", d / "pool" / "a" / "one.stl");
  fs::copy_file(kT1 + ".truth.json", d / "pool" / "a" / "one.truth.json");
  fs::copy_file(std::string(GW_SOURCE_DIR) + "/engine/wire/aortic_035_angled.json", d / "pool" / "a" / "wire.json");
  std::ofstream(d / "pool" / "index.json")
      << R"({"anatomies": [{"name": "one", "set": "a", "mesh": "pool/a/one.stl", "truth": "pool/a/one.truth.json",
                             "wire": "pool/a/wire.json"},
                            {"name": "two", "set": "a", "mesh": "pool/a/one.stl", "truth": "pool/a/one.truth.json"}]})";
  const std::string index = (d / "pool" / "index.json").string();
  const auto sources = gw::resolve_anatomy_sources(index, kIndex);
  REQUIRE(sources.size() == 2);
  CHECK(sources[0].wire == (d / "pool" / "a" / "wire.json").string());
  CHECK(sources[1].wire.empty());
  const std::vector<gw::Anatomy> anatomies = gw::load_anatomies(index, kIndex);
  REQUIRE(anatomies[0].wire);
  CHECK(anatomies[0].wire->diameter_mm == 0.889);
  CHECK_FALSE(anatomies[1].wire);
  const gw::NavigationTask task = gw::make_navigation_task(gw::TaskConfig{}, gw::default_wire_params(), anatomies);
  REQUIRE(task.wires.size() == 2);
  CHECK(gw::wire_of(task, 0).params.diameter_mm == 0.889);
  CHECK(gw::wire_of(task, 1).params.diameter_mm == gw::default_wire_params().diameter_mm);
  CHECK(gw::wire_of(task, 0).nodes != gw::wire_of(task, 1).nodes);  // 450 mm against the coronary wire's length
  for (int a : {0, 1}) {  // an episode on each anatomy starts its own wire, and steps it
    gw::EpisodeState s = gw::reset_episode(task, a, 1, 7);
    CHECK(static_cast<int>(s.wire.x.size()) == gw::wire_of(task, a).nodes);
    CHECK(gw::step_episode(task, s, 0.0).info.problem.empty());
  }
  // A wire the index names that cannot be loaded: an error naming the anatomy and the file.
  std::ofstream(d / "pool" / "bad.json")
      << R"({"anatomies": [{"name": "three", "mesh": "pool/a/one.stl", "truth": "pool/a/one.truth.json",
                             "wire": "pool/a/no_such_wire.json"}]})";
  CHECK_THROWS_WITH(gw::load_anatomies((d / "pool" / "bad.json").string(), kIndex),
                    Catch::Contains("'three'") && Catch::Contains("no_such_wire.json"));
}
