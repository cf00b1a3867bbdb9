// Extraction on swept tubes whose centerline is known exactly.
#include <catch2/catch.hpp>
#include <cmath>

#include "centerline/compare_centerlines.hpp"
#include "centerline/extract_centerline.hpp"
#include "centerline/polyline_tools.hpp"
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

TEST_CASE("Taubin smoothing removes zig-zag noise without pulling a curve inwards", "[centerline]") {
  // Points every 0.5 mm on a circle of radius 10 mm, alternately 0.05 mm in and out.
  std::vector<Eigen::Vector3d> arc;
  for (int i = 0; i <= 40; ++i) {
    const double a = 0.05 * i, r = 10.0 + (i % 2 ? 0.05 : -0.05);
    arc.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
  }
  auto worst_off_circle = [](const std::vector<Eigen::Vector3d>& p) {
    double worst = 0.0;
    for (size_t i = 5; i + 5 < p.size(); ++i) worst = std::max(worst, std::abs(p[i].norm() - 10.0));
    return worst;
  };
  CHECK(worst_off_circle(arc) == Approx(0.05));
  CHECK(worst_off_circle(gw::taubin_smooth_polyline(arc, 4)) < 0.005);
  // The plain Laplacian passes remove the noise too but shrink the circle by ~4 * h^2 / (4 R).
  CHECK(worst_off_circle(gw::smooth_polyline(arc, 4)) > 0.02);
}
