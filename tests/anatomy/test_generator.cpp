// The generator on small trees: truth graph structure, side branches, open ends, deformation.
#include <catch2/catch.hpp>
#include <map>

#include "anatomy_helpers.hpp"
#include "anatomy_gen/deformation.hpp"
#include "anatomy_gen/generate_anatomy.hpp"
#include "anatomy_gen/tree_geometry.hpp"
#include "anatomy_gen/truth_graph.hpp"
#include "base/mesh/validate_mesh.hpp"

namespace {
// A trunk with a side branch leaving mid-way and a Y at its end: 3 targets, 2 bifurcations.
const char* kTree = R"({"name": "side", "branches": [
  {"name": "trunk", "points": [[0,0,0],[0,0,15],[0,0,30]], "radius": 1.5},
  {"name": "side", "parent": 0, "points": [[0,0,15],[8,0,22],[14,0,28]], "radius": 1.2},
  {"name": "a", "parent": 0, "points": [[0,0,30],[-6,0,38],[-9,0,46]], "radius": 1.5},
  {"name": "b", "parent": 0, "points": [[0,0,30],[0,6,38],[0,9,46]], "radius": 1.5}]})";
}  // namespace

TEST_CASE("truth graph: split at side branches, children start at the bifurcation centre", "[anatomy][truth]") {
  const gw::CenterlineGraph g = gw::build_truth_graph(gw::build_tree_geometry(gw::parse_tree_spec(kTree)));
  // trunk -> [trunk 0..15], [trunk 15..30]; side; a; b
  REQUIRE(g.branches.size() == 5);
  REQUIRE(g.bifurcations.size() == 2);
  CHECK(g.inlet.position.norm() < 1e-9);
  CHECK((g.inlet_direction - Eigen::Vector3d::UnitZ()).norm() < 1e-6);
  CHECK(g.inlet.radius == Approx(1.5));
  CHECK((g.bifurcations[0].position - Eigen::Vector3d(0, 0, 15)).norm() < 1e-6);
  CHECK((g.bifurcations[1].position - Eigen::Vector3d(0, 0, 30)).norm() < 1e-6);
  for (const gw::Bifurcation& b : g.bifurcations) {
    CHECK(b.children.size() == 2);
    CHECK((g.branches[b.parent].points.back() - b.position).norm() < 1e-9);
    for (int c : b.children) {
      CHECK(g.branches[c].parent == b.parent);
      CHECK((g.branches[c].points.front() - b.position).norm() < 1e-9);
    }
  }
  REQUIRE(g.targets.size() == 3);
  // Numbered by path length: the side branch (15 + ~19 mm) first.
  CHECK(g.targets[0].id == 1);
  CHECK(g.targets[0].position.isApprox(Eigen::Vector3d(14, 0, 28), 1e-6));
  CHECK(g.targets[0].radius == Approx(1.2));
  for (const auto& b : g.branches)
    for (size_t i = 1; i < b.points.size(); ++i) CHECK((b.points[i] - b.points[i - 1]).norm() <= 0.5 + 1e-6);
}

TEST_CASE("open ends: one boundary loop per inlet/outlet, on the cap circle", "[anatomy][open]") {
  const gw::TreeSpec spec = gw::parse_tree_spec(kTree);
  const gw::GeneratedAnatomy closed = gw::generate_anatomy(spec);
  const gw::GeneratedAnatomy open = gw::generate_anatomy(spec, {true, std::nullopt});
  const gw::MeshReport c = gw::validate_mesh(closed.mesh), o = gw::validate_mesh(open.mesh);
  CHECK(c.closed());
  CHECK(o.boundary_loops == 4);  // inlet + 3 outlets
  CHECK(o.non_manifold_edges == 0);
  CHECK(o.components == 1);
  CHECK(o.degenerate_faces == 0);
  CHECK(o.faces < c.faces);
  // Every boundary vertex lies on one of the end circles (plane and radius).
  const gw::TreeGeometry geometry = gw::build_tree_geometry(spec);
  std::map<std::pair<int, int>, int> use;
  for (Eigen::Index f = 0; f < open.mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = open.mesh.F(f, k), b = open.mesh.F(f, (k + 1) % 3);
      ++use[{std::min(a, b), std::max(a, b)}];
    }
  int boundary_vertices = 0;
  for (const auto& [edge, count] : use) {
    if (count != 1) continue;
    const Eigen::Vector3d p = open.mesh.V.row(edge.first);
    double best = 1e9;
    for (const gw::EndCap& cap : geometry.caps) {
      const Eigen::Vector3d d = p - cap.center;
      const double h = d.dot(cap.normal);
      best = std::min(best, std::abs(h) + std::abs((d - h * cap.normal).norm() - cap.radius));
    }
    CHECK(best < 1e-6);
    ++boundary_vertices;
  }
  CHECK(boundary_vertices > 40);
}

TEST_CASE("the deformation field: identity at phase 0, documented values at phase 1", "[anatomy][deform]") {
  gw::DeformationSpec d;
  d.present = true;
  d.center = Eigen::Vector3d(1, 2, 3);
  d.axis = Eigen::Vector3d::UnitZ();
  d.radial_contraction = 0.1;
  d.axial_shortening = 0.2;
  d.twist_deg_per_cm = 9.0;
  const Eigen::Vector3d x(11, 2, 23);  // 10 mm off axis, 20 mm up
  CHECK((gw::deform_point(d, x, 0.0) - x).norm() < 1e-12);
  // Phase 1: radial 10 -> 9 mm, height 20 -> 16 mm, turned by 18 degrees about z.
  const double a = 18.0 * M_PI / 180.0;
  const Eigen::Vector3d expected = d.center + Eigen::Vector3d(9 * std::cos(a), 9 * std::sin(a), 16);
  CHECK((gw::deform_point(d, x, 1.0) - expected).norm() < 1e-9);
  // Half phase: half the amplitudes.
  const double h = 9.0 * M_PI / 180.0;
  CHECK((gw::deform_point(d, x, 0.5) - (d.center + Eigen::Vector3d(9.5 * std::cos(h), 9.5 * std::sin(h), 18))).norm() <
        1e-9);
}

TEST_CASE("a deformed spec keeps children on their parents", "[anatomy][deform]") {
  gw::TreeSpec spec = gw::parse_tree_spec(kTree);
  gw::DeformationSpec d;
  d.present = true;
  d.axis = Eigen::Vector3d(0.3, 0.2, 1).normalized();
  d.radial_contraction = 0.15;
  d.axial_shortening = 0.1;
  d.twist_deg_per_cm = 6.0;
  const gw::TreeSpec moved = gw::deform_spec(spec, d, 1.0);
  for (size_t b = 1; b < moved.branches.size(); ++b) {
    const auto loc = gw::locate_on_branch(moved.branches[moved.branches[b].parent], moved.branches[b].points.front());
    CHECK(loc.distance < 1e-6);
  }
  CHECK_NOTHROW(gw::build_tree_geometry(moved));
}

TEST_CASE("the committed deformed coronary is the coronary moved by its field at phase 1", "[anatomy][deform]") {
  const gw::TreeSpec rest = gw::read_tree_spec(gw::test::repo("anatomies/test/coronary/coronary.spec.json"));
  const gw::TreeSpec deformed =
      gw::read_tree_spec(gw::test::repo("anatomies/test/coronary_deformed/coronary_deformed.spec.json"));
  REQUIRE(rest.deformation.present);
  CHECK(rest.deformation.phase == 0.0);
  CHECK(deformed.deformation.phase == 1.0);
  const gw::CenterlineGraph a = gw::read_centerline(gw::test::repo("anatomies/test/coronary/coronary.truth.json"));
  const gw::CenterlineGraph b =
      gw::read_centerline(gw::test::repo("anatomies/test/coronary_deformed/coronary_deformed.truth.json"));
  REQUIRE(a.bifurcations.size() == b.bifurcations.size());
  // Bifurcations sit on parent control points, which the field maps exactly.
  for (size_t i = 0; i < a.bifurcations.size(); ++i)
    CHECK((gw::deform_point(rest.deformation, a.bifurcations[i].position, 1.0) - b.bifurcations[i].position).norm() <
          1e-5);
  CHECK((gw::deform_point(rest.deformation, a.inlet.position, 1.0) - b.inlet.position).norm() < 1e-5);
  // The whole truth moved by the field stays close to the truth of the moved spec.
  gw::CenterlineGraph moved = a;
  gw::deform_centerline(moved, rest.deformation, 1.0);
  for (const auto& t : moved.targets) {
    double best = 1e9;
    for (const auto& u : b.targets) best = std::min(best, (t.position - u.position).norm());
    CHECK(best < 1e-5);
  }
}
