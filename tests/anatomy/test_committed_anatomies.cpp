// Every committed anatomy: a closed, single-component, 2-manifold surface whose volume is that
// of its tubes, with its ground-truth centreline inside at the right distance from the wall.
#include <catch2/catch.hpp>
#include <filesystem>
#include <set>

#include "anatomy_helpers.hpp"
#include "base/graph/centerline_graph.hpp"
#include "base/mesh/load_mesh.hpp"
#include "base/mesh/validate_mesh.hpp"

using gw::test::committed_anatomies;

TEST_CASE("the index lists the fixed anatomy layout and every file exists", "[anatomy][set]") {
  const auto entries = committed_anatomies();
  std::set<std::string> names;
  for (const auto& e : entries) {
    INFO(e.name);
    names.insert(e.set + "/" + e.name);
    for (const std::string& path : {e.mesh, e.truth, e.spec}) CHECK(std::filesystem::exists(path));
  }
  const std::set<std::string> expected = {
      "train/t1_straight_y",       "train/t2_curved_straight_exit", "train/t3_out_of_plane_steep",
      "train/t4_s_curving_back",   "sensitivity/base",              "sensitivity/rotated",
      "sensitivity/translated",    "sensitivity/var1",              "sensitivity/var2",
      "sensitivity/var3",          "test/training_patterns_tree",   "test/unseen_4_bifurcations",
      "test/coronary",             "test/coronary_deformed",        "validation/rca_validation",
      "validation/rca_validation_deformed", "validation/pl_validation", "validation/syn_validation",
      "junctions/coronary_trifurcation", "junctions/close_forks",
      "junctions/coronary_trifurcation_outer", "junctions/close_forks_outer",
      "train_junctions/t5_trifurcation_planar", "train_junctions/t6_trifurcation_spread"};
  CHECK(names == expected);
}

TEST_CASE("every committed mesh is closed, one component, manifold, outward, and not degenerate", "[anatomy][mesh]") {
  for (const auto& e : committed_anatomies()) {
    INFO(e.name);
    const gw::TriangleMesh mesh = gw::load_mesh(e.mesh);
    const gw::MeshReport r = gw::validate_mesh(mesh);
    CHECK(r.ok());
    CHECK(r.boundary_edges == 0);
    CHECK(r.non_manifold_edges == 0);
    CHECK(r.components == 1);
    CHECK(r.degenerate_faces == 0);
    CHECK(r.volume > 0.0);  // outward orientation
    CHECK(r.warnings.empty());
  }
}

TEST_CASE("mesh volume matches the analytic volume of the union of tubes", "[anatomy][volume]") {
  for (const auto& e : committed_anatomies()) {
    INFO(e.name);
    const gw::MeshReport r = gw::validate_mesh(gw::load_mesh(e.mesh));
    const double reference = gw::test::tube_union_volume(gw::read_centerline(e.truth));
    INFO("mesh " << r.volume << " mm^3, tube union " << reference << " mm^3");
    // The junction fillets add a little volume; facets (chords) remove a little.
    CHECK(std::abs(r.volume - reference) / reference < 0.03);
  }
}

TEST_CASE("truth centrelines lie inside, at a distance from the wall close to their radius", "[anatomy][truth]") {
  for (const auto& e : committed_anatomies()) {
    INFO(e.name);
    const gw::TriangleMesh mesh = gw::load_mesh(e.mesh);
    const gw::CenterlineGraph g = gw::read_centerline(e.truth);
    REQUIRE(!g.targets.empty());
    std::vector<Eigen::Vector3d> ends{g.inlet.position};
    for (const auto& t : g.targets) ends.push_back(t.position);
    int checked = 0, inside_checked = 0;
    double worst = 0.0;
    for (const auto& b : g.branches)
      for (size_t i = 0; i < b.points.size(); i += 3) {
        const Eigen::Vector3d& p = b.points[i];
        const double r = b.radii[i];
        double to_end = 1e9, to_junction = 1e9;
        for (const auto& q : ends) to_end = std::min(to_end, (p - q).norm());
        for (const auto& j : g.bifurcations) to_junction = std::min(to_junction, (p - j.position).norm());
        if (to_end < 1.5 * r) continue;  // on or next to a flat cap: the cap is the nearest wall
        const double d = gw::test::distance_to_mesh(mesh, p, 4.0 * r);
        INFO("point " << p.transpose() << " radius " << r << " wall distance " << d);
        if (to_junction > 8.0 * r) {
          // Plain tube: the wall is the tube (chordal facets sit within r/100 inside it).
          CHECK(std::abs(d - r) < 0.03 * r + 0.01);
          worst = std::max(worst, std::abs(d - r) / r);
        } else {
          // Junction: the lumen only widens (fillets, the other branch).
          CHECK(d > 0.97 * r - 0.01);
          CHECK(d < 3.0 * r);
        }
        if (checked++ % 10 == 0) {
          CHECK(gw::test::winding_number(mesh, p) == Approx(1.0).margin(1e-3));
          ++inside_checked;
        }
      }
    INFO("worst relative wall-distance error " << worst);
    CHECK(checked > 20);
    CHECK(inside_checked > 2);
  }
}
