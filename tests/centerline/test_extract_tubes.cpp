// Extraction on swept tubes whose centerline is known exactly.
#include <catch2/catch.hpp>

#include "centerline/extract/compare_centerlines.hpp"
#include "centerline/extract/extract_centerline.hpp"
#include "tube_mesh.hpp"

using namespace gw;

namespace {
CenterlineAccuracy run(const TriangleMesh& mesh, const CenterlineGraph& truth, CenterlineStats* stats = nullptr) {
  CenterlineOptions opt;
  opt.inlet = truth.inlet.position;
  const CenterlineGraph g = extract_centerline(mesh, opt, stats);
  const CenterlineAccuracy a = compare_centerlines(g, truth);
  INFO(accuracy_to_json(a));
  UNSCOPED_INFO(accuracy_to_json(a));
  WARN(accuracy_to_json(a));
  return a;
}
}  // namespace

TEST_CASE("straight closed cylinder: one branch on the axis with the right radius") {
  const auto axis = test::arc_axis(40.0, 0.0, 0.0, 80);
  const auto truth = test::tube_truth(axis, 2.0);
  const CenterlineAccuracy a = run(test::make_tube(axis, 2.0, 32, true), truth);
  CHECK(a.same_topology);
  CHECK(a.mean_distance <= 0.05);
  CHECK(a.p95_distance <= 0.15);
  CHECK(a.mean_radius_error <= 0.10);
}

TEST_CASE("curved closed tube (quarter turn, bend radius 5 tube radii)") {
  const auto axis = test::arc_axis(0.0, 10.0, M_PI / 2, 120);
  const auto truth = test::tube_truth(axis, 2.0);
  const CenterlineAccuracy a = run(test::make_tube(axis, 2.0, 32, true), truth);
  CHECK(a.same_topology);
  CHECK(a.mean_distance <= 0.05);
  CHECK(a.p95_distance <= 0.15);
  CHECK(a.mean_radius_error <= 0.10);
}

TEST_CASE("open, noisy curved tube: ends are capped and become the terminals") {
  const auto axis = test::arc_axis(0.0, 12.0, M_PI / 2, 120);
  const auto truth = test::tube_truth(axis, 2.0);
  CenterlineStats stats;
  const CenterlineAccuracy a = run(test::make_tube(axis, 2.0, 32, false, 0.1), truth, &stats);
  CHECK(stats.capped_holes == 2);
  CHECK(a.same_topology);
  CHECK(a.mean_distance <= 0.05);
  CHECK(a.p95_distance <= 0.15);
  CHECK(a.mean_radius_error <= 0.10);
}
