// Branch origins on a vessel much wider than the branch (issue 35: the aortic arch's supra-aortic
// branches). The skeleton of such a junction runs along the wide vessel's wall between the
// origins; the extraction must still put every origin on the wide vessel's axis.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "centerline/compare_centerlines.hpp"
#include "centerline/cross_section.hpp"
#include "centerline/extract_centerline.hpp"
#include "centerline/open_cross_section.hpp"
#include "centerline/vessel_wall.hpp"
#include "anatomy_gen/generate_anatomy.hpp"
#include "tube_mesh.hpp"

using namespace gw;

TEST_CASE("a cross-section through a wall opening is fitted on the wall around it", "[centerline]") {
  // A straight tube of radius 10 along x with a window cut into its +y side (60 degrees wide,
  // x in [20, 30]): rays from a point 3 mm below the window leave through it.
  TriangleMesh tube = test::make_tube(test::arc_axis(50.0, 0.0, 0.0, 50), 10.0, 96, false);
  std::vector<Eigen::Vector3i> kept;
  for (Eigen::Index f = 0; f < tube.F.rows(); ++f) {
    const Eigen::Vector3d c = (tube.V.row(tube.F(f, 0)) + tube.V.row(tube.F(f, 1)) + tube.V.row(tube.F(f, 2))).transpose() / 3.0;
    const double angle = std::atan2(c.z(), c.y());  // 0 at +y
    if (c.x() > 20 && c.x() < 30 && std::abs(angle) < M_PI / 6) continue;
    kept.push_back(tube.F.row(f).transpose());
  }
  REQUIRE(kept.size() < static_cast<size_t>(tube.F.rows()));
  tube.F.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t i = 0; i < kept.size(); ++i) tube.F.row(static_cast<Eigen::Index>(i)) = kept[i].transpose();
  const VesselWall wall(tube);
  const Eigen::Vector3d p(25.0, 7.0, 0.5), tangent(1.0, 0.0, 0.0);
  // The plain fit refuses it: a ray escapes through the window.
  CHECK_FALSE(fit_cross_section(wall, p, tangent, 4.0 * wall.distance(p)).tube);
  const CrossSection open = fit_open_cross_section(wall, p, tangent, 10.0 * wall.distance(p));
  REQUIRE(open.tube);
  // The tube's polygon (96 sides) is within 0.06% of the circle; the window takes 60 of 360 degrees.
  CHECK((open.centre - Eigen::Vector3d(25.0, 0.0, 0.0)).norm() < 0.02 * 10.0);
  CHECK(open.radius == Approx(10.0).epsilon(0.02));
  CHECK(std::isinf(open.elongation));  // never a clean tube for the junction's line fits
  // A window wider than 120 degrees leaves less than 240 degrees of wall: refused, not guessed.
  std::vector<Eigen::Vector3i> narrow;
  for (Eigen::Index f = 0; f < tube.F.rows(); ++f) {
    const Eigen::Vector3d c = (tube.V.row(tube.F(f, 0)) + tube.V.row(tube.F(f, 1)) + tube.V.row(tube.F(f, 2))).transpose() / 3.0;
    if (c.x() > 20 && c.x() < 30 && std::abs(std::atan2(c.z(), c.y())) < 0.45 * M_PI) continue;
    narrow.push_back(tube.F.row(f).transpose());
  }
  TriangleMesh wide_window = tube;
  wide_window.F.resize(static_cast<Eigen::Index>(narrow.size()), 3);
  for (size_t i = 0; i < narrow.size(); ++i) wide_window.F.row(static_cast<Eigen::Index>(i)) = narrow[i].transpose();
  CHECK_FALSE(fit_open_cross_section(VesselWall(wide_window), p, tangent, 10.0 * wall.distance(p)).tube);
}

TEST_CASE("aortic arches: the supra-aortic origins lie on the arch's axis", "[centerline][anatomy]") {
  // The generator's Type I, II and III arches (anatomies/segmentation, 24 mm aorta, 8-13 mm branches
  // 13-26 mm apart), smooth surfaces. The bar of issue 35: mean distance <= 5% of the radius, every true
  // bifurcation within 0.5 of its parent's radius.
  for (int type : {1, 2, 3}) {
    INFO("arch type " << type);
    const std::string spec = std::string(GW_SOURCE_DIR) + "/anatomies/segmentation/arch_type" + std::to_string(type) + ".spec.json";
    const GeneratedAnatomy arch = generate_anatomy(read_tree_spec(spec), AnatomyOptions{});
    CenterlineOptions options;
    options.inlet = arch.truth.inlet.position;
    const CenterlineAccuracy acc = compare_centerlines(extract_centerline(arch.mesh, options), arch.truth);
    INFO(accuracy_to_json(acc));
    CHECK(acc.same_topology);
    CHECK(acc.mean_distance <= 0.05);
    CHECK(acc.max_bifurcation_offset <= 0.5);
  }
}
