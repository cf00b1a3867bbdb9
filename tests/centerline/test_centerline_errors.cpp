// What extraction refuses, repairs, and how it says so.
#include <catch2/catch.hpp>

#include "centerline/centerline_cache.hpp"
#include "centerline/compare_centerlines.hpp"
#include "centerline/extract_centerline.hpp"
#include "centerline/target_table.hpp"
#include "tube_mesh.hpp"
#include "../mesh/mesh_files.hpp"

using namespace gw;

TEST_CASE("surfaces that cannot become a closed vessel are refused with a message", "[centerline][errors]") {
  TriangleMesh empty;
  empty.V.resize(0, 3);
  empty.F.resize(0, 3);
  CHECK_THROWS_WITH(extract_centerline(empty), Catch::Contains("no faces"));

  TriangleMesh sheet;  // a flat square: capping its one hole encloses nothing
  sheet.V.resize(4, 3);
  sheet.V << 0, 0, 0, 10, 0, 0, 10, 10, 0, 0, 10, 0;
  sheet.F.resize(2, 3);
  sheet.F << 0, 1, 2, 0, 2, 3;
  CHECK_THROWS_AS(extract_centerline(sheet), std::runtime_error);

  TriangleMesh tube = test::make_tube(test::arc_axis(20.0, 0, 0, 20), 2.0, 16, true);
  tube.V(3, 1) = std::nan("");
  CHECK_THROWS_WITH(extract_centerline(tube), Catch::Contains("non-finite"));

  CenterlineOptions bad;
  bad.spacing = 0;
  CHECK_THROWS_AS(extract_centerline(test::make_tube(test::arc_axis(20.0, 0, 0, 20), 2.0, 16, true), bad),
                  std::invalid_argument);
}

TEST_CASE("extra pieces are dropped with a warning, open ends are capped and reported", "[centerline][errors]") {
  const auto axis = test::arc_axis(30.0, 0, 0, 60);
  TriangleMesh tube = test::make_tube(axis, 2.0, 24, false);
  // A small closed cube far from the tube: debris from a segmentation.
  TriangleMesh cube = test::unit_cube();
  const Eigen::Index nv = tube.V.rows(), nf = tube.F.rows();
  tube.V.conservativeResize(nv + 8, 3);
  tube.F.conservativeResize(nf + 12, 3);
  tube.V.bottomRows(8) = (cube.V.array() + 50.0).matrix();
  tube.F.bottomRows(12) = (cube.F.array() + static_cast<int>(nv)).matrix();
  CenterlineStats stats;
  const CenterlineGraph g = extract_centerline(tube, {}, &stats);
  CHECK(stats.dropped_components == 1);
  CHECK(stats.capped_holes == 2);
  CHECK(stats.repairs.size() == 2);
  CHECK(stats.warnings.empty());
  REQUIRE(g.targets.size() == 1);
  // The ends of an open tube are its terminals.
  const bool forward = (g.inlet.position - axis.front()).norm() < (g.inlet.position - axis.back()).norm();
  CHECK((g.inlet.position - (forward ? axis.front() : axis.back())).norm() < 0.5);
  CHECK((g.targets[0].position - (forward ? axis.back() : axis.front())).norm() < 0.5);
}

TEST_CASE("the same mesh gives (nearly) the same graph, whatever ran before", "[centerline]") {
  // CGAL's MCF walks sets ordered by pointer, so its raw skeleton can differ a little
  // between calls; re-centring must make that invisible (the cache makes it exact).
  const auto axis = test::arc_axis(0.0, 12.0, M_PI / 2, 90);
  const TriangleMesh tube = test::make_tube(axis, 1.5, 32, true);
  CenterlineOptions options;
  options.inlet = axis.front();
  const CenterlineGraph first = extract_centerline(tube, options);
  extract_centerline(test::make_tube(test::arc_axis(25.0, 0, 0, 40), 2.0, 20, true));
  for (int run = 0; run < 3; ++run) {
    const CenterlineAccuracy a = compare_centerlines(extract_centerline(tube, options), first);
    INFO(accuracy_to_json(a));
    CHECK(a.same_topology);
    CHECK(a.mean_distance <= 0.02);
    CHECK(a.max_distance <= 0.1);
    CHECK(a.max_terminal_offset <= 0.1);
  }
}

TEST_CASE("cache: keyed by content and options, second call is a hit", "[centerline][cache]") {
  const std::string dir = test::scratch_path("centerline_cache");
  std::filesystem::remove_all(dir);
  const std::string mesh = test::scratch_path("cache_tube.stl");
  test::write_binary_stl(mesh, test::make_tube(test::arc_axis(25.0, 0, 0, 50), 2.0, 24, true));
  CenterlineOptions options;
  const std::string key = centerline_cache_key(mesh, 1.0, options);
  CHECK(key.size() == 16);
  CHECK(centerline_cache_key(mesh, 2.0, options) != key);
  CenterlineOptions other = options;
  other.inlet = Eigen::Vector3d(25, 0, 0);
  CHECK(centerline_cache_key(mesh, 1.0, other) != key);

  CacheOptions cache{true, dir};
  bool hit = true;
  const CenterlineGraph a = cached_extract_centerline(mesh, 1.0, options, cache, nullptr, &hit);
  CHECK_FALSE(hit);
  CHECK(std::filesystem::exists(dir + "/" + key + ".json"));
  const CenterlineGraph b = cached_extract_centerline(mesh, 1.0, options, cache, nullptr, &hit);
  CHECK(hit);
  CHECK(centerline_to_json(a) == centerline_to_json(b));

  // A corrupt entry is recomputed, not trusted.
  test::write_text(dir + "/" + key + ".json", "{not json");
  cached_extract_centerline(mesh, 1.0, options, cache, nullptr, &hit);
  CHECK_FALSE(hit);
  CHECK_THROWS_WITH(centerline_cache_key(test::scratch_path("missing.stl"), 1.0, options),
                    Catch::Contains("cannot read mesh file"));
}

TEST_CASE("target table lists every target with its path and bifurcations", "[centerline]") {
  CenterlineGraph g;
  g.branches = {{0, -1, {{0, 0, 0}, {0, 0, 10}}, {2, 2}},
                {1, 0, {{0, 0, 10}, {5, 0, 15}}, {1, 1}},
                {2, 0, {{0, 0, 10}, {-3, 0, 30}}, {1, 1}}};
  g.bifurcations = {{0, {0, 0, 10}, 0, {1, 2}}};
  g.inlet = {0, {0, 0, 0}, 0, 2.0};
  number_targets(g);
  const std::string table = format_target_table(g);
  CHECK(table.find("2 target(s), 1 bifurcation(s)") != std::string::npos);
  CHECK(table.find("   1  (5.00, 0.00, 15.00)") != std::string::npos);
  CHECK(table.find("17.07") != std::string::npos);  // 10 + 5 sqrt 2
  CHECK(table.find("0(1)") != std::string::npos);
  CHECK(table.find("0(2)") != std::string::npos);
}
