// The mesh intake (intake_surface, close_surface): what a user's surface gets repaired for, how
// each repair is reported, and what is still refused.
#include <catch2/catch.hpp>

#include <cmath>

#include "centerline/compare_centerlines.hpp"
#include "centerline/extract_centerline.hpp"
#include "centerline/intake_surface.hpp"
#include "centerline/prepare_surface.hpp"
#include "base/mesh/load_mesh.hpp"
#include "base/mesh/validate_mesh.hpp"
#include "tube_mesh.hpp"
#include "../mesh/mesh_files.hpp"

using namespace gw;

namespace {

TriangleMesh flipped(TriangleMesh m) {
  m.F.col(1).swap(m.F.col(2));
  return m;
}

TriangleMesh joined(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return m;
}

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& l : lines)
    if (l.find(text) != std::string::npos) return true;
  return false;
}

double signed_volume(const TriangleMesh& m) { return validate_mesh(m).volume; }

}  // namespace

TEST_CASE("a closed surface whose normals point into the lumen is reversed and says so", "[centerline][intake]") {
  const auto axis = test::arc_axis(40.0, 0, 0, 40);
  const TriangleMesh inward = flipped(test::make_tube(axis, 2.0, 24, true));
  REQUIRE(signed_volume(inward) < 0);
  const ClosedSurface c = close_surface(inward);
  CHECK(c.flipped);
  CHECK_FALSE(c.wrapped);
  CHECK(mentions(c.repairs, "reversed"));
  CHECK(signed_volume(c.mesh) > 0);
  CHECK(c.volume == Approx(signed_volume(c.mesh)).epsilon(1e-9));

  // The same surface facing outwards needs nothing.
  const ClosedSurface clean = close_surface(test::make_tube(axis, 2.0, 24, true));
  CHECK(clean.repairs.empty());
}

TEST_CASE("an open, inward tube is capped and reversed, its ends stay the terminals", "[centerline][intake]") {
  const auto axis = test::arc_axis(30.0, 25.0, 1.2, 60);
  const TriangleMesh open_inward = flipped(test::make_tube(axis, 1.5, 24, false));
  CenterlineStats stats;
  const CenterlineGraph g = extract_centerline(open_inward, {}, &stats);
  CHECK(mentions(stats.repairs, "reversed"));
  CHECK(mentions(stats.repairs, "2 of them round vessel ends"));
  REQUIRE(g.targets.size() == 1);
  const CenterlineAccuracy a = compare_centerlines(g, test::tube_truth(axis, 1.5));
  CHECK(a.mean_distance < 0.05);
}

TEST_CASE("islands are dropped by area with their count and size, vessel-sized pieces are not", "[centerline][intake]") {
  const auto axis = test::arc_axis(40.0, 0, 0, 40);
  TriangleMesh m = test::make_tube(axis, 2.0, 24, true);
  for (int k = 0; k < 3; ++k) {  // three 1 mm debris cubes, as marching cubes leaves around a mask
    TriangleMesh cube = test::unit_cube();
    cube.V.rowwise() += Eigen::RowVector3d(10.0 * k, 8.0, 0.0);
    m = joined(m, cube);
  }
  const ClosedSurface c = close_surface(m);
  CHECK(c.dropped_components == 3);
  CHECK(c.dropped_faces == 36);
  CHECK(c.largest_dropped_area == Approx(6.0));
  CHECK(mentions(c.repairs, "dropped 3 island(s) of 36 faces"));
  CHECK_FALSE(c.wrapped);
  CHECK(c.mesh.F.rows() == test::make_tube(axis, 2.0, 24, true).F.rows());
}

TEST_CASE("two overlapping tube pieces are alpha-wrapped into one surface with the right tree", "[centerline][intake]") {
  // A Y built as two separate closed tubes that overlap (a phantom modelled without a boolean
  // union): the trunk and one exit along x, the other exit leaving at 40 degrees.
  const double r = 1.5;
  const auto straight = test::arc_axis(70.0, 0, 0, 70);
  std::vector<Eigen::Vector3d> side;
  const Eigen::Vector3d start(30.0, 0, 0), dir(std::cos(0.7), std::sin(0.7), 0.0);
  for (int i = 0; i <= 40; ++i) side.push_back(start + dir * i);
  const TriangleMesh pieces = joined(test::make_tube(straight, r, 24, true), test::make_tube(side, r, 24, true));
  REQUIRE(validate_mesh(pieces).components == 2);

  const ClosedSurface c = close_surface(pieces);
  CHECK(c.wrapped);
  CHECK(c.kept_pieces == 2);
  CHECK(mentions(c.repairs, "alpha-wrapped (2 separate vessel-sized pieces)"));
  CHECK(c.wrap_scale_radius == Approx(r).epsilon(0.1));  // the thin vessels' radius, measured by rays
  const MeshReport out = validate_mesh(c.mesh);
  CHECK(out.closed());
  CHECK(out.manifold());
  CHECK(out.components == 1);
  CHECK(out.volume > 0);

  CenterlineOptions options;
  options.inlet = Eigen::Vector3d(0, 0, 0);
  const CenterlineGraph g = extract_centerline(c, options);
  CHECK(g.targets.size() == 2);
  REQUIRE(g.bifurcations.size() == 1);
  CHECK((g.bifurcations[0].position - start).norm() < r);
  CHECK((g.inlet.position - straight.front()).norm() < 1.0);
}

TEST_CASE("a non-manifold fin on a tube is split off by the soup repair and dropped", "[centerline][intake]") {
  TriangleMesh m = test::make_tube(test::arc_axis(40.0, 0, 0, 40), 2.0, 24, true);
  // A small triangle fan hanging on an existing edge: that edge now has three faces.
  const int a = m.F(100, 0), b = m.F(100, 1);
  const Eigen::Index nv = m.V.rows();
  m.V.conservativeResize(nv + 1, 3);
  m.V.row(nv) = 0.5 * (m.V.row(a) + m.V.row(b)) + Eigen::RowVector3d(0, 0, 0.3);
  m.F.conservativeResize(m.F.rows() + 1, 3);
  m.F.row(m.F.rows() - 1) << a, b, static_cast<int>(nv);
  REQUIRE(validate_mesh(m).non_manifold_edges == 1);
  const ClosedSurface c = close_surface(m);
  CHECK(c.soup_repaired);
  CHECK(mentions(c.repairs, "soup repaired"));
  const MeshReport out = validate_mesh(c.mesh);
  CHECK(out.closed());
  CHECK(out.manifold());
  CHECK(out.components == 1);
  CHECK(out.volume > 0);
}

TEST_CASE("a forced wrap stays within its offset of the input and keeps the centerline", "[centerline][intake]") {
  const auto axis = test::arc_axis(30.0, 25.0, 1.2, 60);
  SurfaceRepairOptions wrap;
  wrap.force_wrap = true;
  const ClosedSurface c = close_surface(test::make_tube(axis, 1.5, 32, true), wrap);
  REQUIRE(c.wrapped);
  CHECK(c.wrap_alpha > 0);
  CHECK(c.wrap_offset < 0.1 * 1.5);
  // The radius grows by about the offset, the axis stays: mean radius 2V/A within offset + 5%.
  CHECK(std::abs(c.mean_radius() - 1.5) < c.wrap_offset + 0.075);
  const CenterlineAccuracy a = compare_centerlines(extract_centerline(c), test::tube_truth(axis, 1.5));
  CHECK(a.same_topology);
  CHECK(a.mean_distance < 0.05);
}

TEST_CASE("intake: a surface in metres is scaled by 1000 and said so, --scale overrides", "[centerline][intake]") {
  TriangleMesh tube = test::make_tube(test::arc_axis(40.0, 0, 0, 40), 2.0, 24, true);
  tube.V *= 0.001;
  const std::string path = test::scratch_path("intake_metres.stl");
  test::write_binary_stl(path, tube);
  const IntakeSurface s = intake_surface(path);
  CHECK(s.scale == 1000.0);
  CHECK(mentions(s.repairs, "read as metres"));
  // 2V/A of a capped tube of radius r and length L: r L / (L + r) (24-gon sections: 1% less).
  CHECK(s.closed.mean_radius() == Approx(2.0 * 40.0 / 42.0).epsilon(0.02));
  CHECK(intake_report_json(s).find("\"scale_detected\":true") != std::string::npos);

  IntakeOptions given;
  given.scale = 1.0;
  const IntakeSurface kept = intake_surface(path, given);
  CHECK(kept.scale == 1.0);
  CHECK(kept.repairs.empty());
  CHECK(mentions(kept.warnings, "probably in metres"));
}

TEST_CASE("intake: a clean closed mm surface is used exactly as loaded", "[centerline][intake]") {
  const TriangleMesh tube = test::make_tube(test::arc_axis(40.0, 0, 0, 40), 2.0, 24, true);
  const std::string path = test::scratch_path("intake_clean.ply");
  test::write_ply(path, tube);
  const IntakeSurface s = intake_surface(path);
  CHECK(s.repairs.empty());
  CHECK(s.scale == 1.0);
  const TriangleMesh loaded = load_mesh(path);
  CHECK(s.wall.V == loaded.V);
  CHECK(s.wall.F == loaded.F);
}

TEST_CASE("intake: unusable surfaces get an error naming the file and the problem", "[centerline][intake]") {
  const std::string empty = test::scratch_path("intake_empty.stl");
  test::write_text(empty, "");
  CHECK_THROWS_WITH(intake_surface(empty), Catch::Contains(empty) && Catch::Contains("empty file"));

  TriangleMesh sheet;  // a flat 10 x 10 mm grid: one open sheet, capping it encloses nothing
  const int n = 11;
  sheet.V.resize(n * n, 3);
  sheet.F.resize(2 * (n - 1) * (n - 1), 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sheet.V.row(i * n + j) << i, j, 0.0;
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      sheet.F.row(f++) << i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1;
      sheet.F.row(f++) << i * n + j, (i + 1) * n + j + 1, i * n + j + 1;
    }
  const std::string flat = test::scratch_path("intake_sheet.obj");
  test::write_obj(flat, sheet);
  CHECK_THROWS_WITH(intake_surface(flat), Catch::Contains(flat) && Catch::Contains("encloses no volume"));

  TriangleMesh tube = test::make_tube(test::arc_axis(20.0, 0, 0, 20), 2.0, 16, true);
  tube.V(3, 1) = std::nan("");
  const std::string nan = test::scratch_path("intake_nan.obj");
  test::write_obj(nan, tube);
  CHECK_THROWS_WITH(intake_surface(nan), Catch::Contains(nan) && Catch::Contains("NaN"));

  IntakeOptions negative;
  negative.scale = -1.0;
  CHECK_THROWS_WITH(intake_surface(nan, negative), Catch::Contains("scale"));
}
