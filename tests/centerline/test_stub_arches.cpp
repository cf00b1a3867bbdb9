// Vessel ends cut flat (centerline/flat_ends.hpp) and the great vessels of an arch cut to stubs: a capped tube's two
// end disks are found (centre, radius, outward normal) and its wall is not taken for one; on the nine stub arches
// of the validation set (anatomies/validation/arches/*_stub*, stubs 1-3 of their radii long) every true target has
// an extracted one within half its radius, where the first skeleton had only the aorta (centerline/README.md).
#include <catch2/catch.hpp>
#include <string>

#include "anatomy_gen/generate_anatomy.hpp"
#include "centerline/extract_centerline.hpp"
#include "centerline/flat_ends.hpp"
#include "tube_mesh.hpp"

using namespace gw;

TEST_CASE("a flat-capped tube has two flat ends, its wall none", "[centerline]") {
  const TriangleMesh tube = test::make_tube(test::arc_axis(30.0, 20.0, 1.0, 60), 2.0, 24, true);
  const std::vector<SurfaceCap> ends = flat_ends(tube, VesselWall(tube));
  REQUIRE(ends.size() == 2);
  const Eigen::Vector3d start(0, 0, 0), end(20.0 * std::sin(1.0), 20.0 * (1 - std::cos(1.0)), 0.0);
  const Eigen::Vector3d out_end(std::cos(1.0), std::sin(1.0), 0.0);
  for (const SurfaceCap& e : ends) {
    const bool at_start = (e.centre - start).norm() < (e.centre - end).norm();
    CHECK((e.centre - (at_start ? start : end)).norm() < 0.05);
    CHECK(e.radius == Approx(2.0).epsilon(0.05));
    CHECK(e.normal.dot(at_start ? Eigen::Vector3d(-1, 0, 0) : out_end) > 0.999);
  }
  const TriangleMesh open = test::make_tube(test::arc_axis(30.0, 20.0, 1.0, 60), 2.0, 24, false);
  CHECK(flat_ends(open, VesselWall(open)).empty());  // open: no disk
}

TEST_CASE("the great vessels of an arch cut to stubs 1-3 radii long are found", "[centerline][anatomy]") {
  for (int type : {1, 2, 3})
    for (int k : {1, 2, 3}) {
      const std::string name = "arch_val_type" + std::to_string(type) + "_stub" + std::to_string(k);
      INFO(name);
      const GeneratedAnatomy arch =
          generate_anatomy(read_tree_spec(std::string(GW_SOURCE_DIR) + "/anatomies/validation/arches/" + name +
                                          ".spec.json"),
                           AnatomyOptions{});
      CenterlineOptions options;
      options.inlet = arch.truth.inlet.position;
      CenterlineStats stats;
      const CenterlineGraph g = extract_centerline(arch.mesh, options, &stats);
      CHECK(stats.missed_ends == 3);  // the first skeleton: the aorta alone
      REQUIRE(g.targets.size() == 4);
      for (const Terminal& t : arch.truth.targets) {
        double nearest = 1e9;
        for (const Terminal& e : g.targets) nearest = std::min(nearest, (e.position - t.position).norm());
        CHECK(nearest <= 0.5 * t.radius);
      }
      // Type I, stubs of one radius: the brachiocephalic and left common carotid origins, 12.6 mm apart on a
      // 12 mm aorta, come out as one junction (a trifurcation); everywhere else the truth's three.
      CHECK(g.bifurcations.size() == (type == 1 && k == 1 ? 2u : 3u));
    }
}
