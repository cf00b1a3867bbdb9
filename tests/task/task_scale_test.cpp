// Task lengths in millimetres (the paper's, TaskScale::kFixed) or from the vessel's walls (kVessel):
// the ostium of a wrong child, the wrong-branch verdict inside its lumen, the control zone, and kAuto's
// choice by the inlet radius (task_config.hpp; docs/vessel_scale.md).
#include <catch2/catch.hpp>
#include <cmath>

#include "task/anatomy.hpp"
#include "task/branch_lumen.hpp"
#include "task/course.hpp"
#include "task/wrong_branch_entered.hpp"
#include "tests/task/hand_made_graphs.hpp"

using Approx = Catch::Detail::Approx;
using Eigen::Vector3d;

namespace {

// An aorta-sized T: root along +y (radius `parent_r`, 60 mm) into a centre at (0, 60, 0); child 1 goes
// straight on (the course to target 1), child 2 leaves along direction (sin a, cos a, 0) with radius 5.
gw::CenterlineGraph wide_t(double parent_r, double angle_deg) {
  const double a = angle_deg * 3.14159265358979323846 / 180.0;
  gw::CenterlineGraph g;
  const Vector3d o(0, 0, 0), c(0, 60, 0), d(std::sin(a), std::cos(a), 0);
  g.inlet.position = o;
  g.inlet.branch = 0;
  g.inlet.radius = parent_r;
  g.inlet_direction = Vector3d::UnitY();
  g.branches.push_back(gwtest::branch(0, -1, gwtest::segment(o, c), parent_r));
  g.branches.push_back(gwtest::branch(1, 0, gwtest::segment(c, c + Vector3d(0, 60, 0)), parent_r));
  g.branches.push_back(gwtest::branch(2, 0, gwtest::segment(c, c + 60.0 * d), 5.0));
  gw::Bifurcation b;
  b.id = 0;
  b.position = c;
  b.parent = 0;
  b.children = {1, 2};
  g.bifurcations.push_back(b);
  for (int leaf : {1, 2}) {
    gw::Terminal t;
    t.position = g.branches[static_cast<size_t>(leaf)].points.back();
    t.branch = leaf;
    t.radius = g.branches[static_cast<size_t>(leaf)].radii.back();
    g.targets.push_back(t);
  }
  gw::number_targets(g);
  return g;
}

int target_on(const gw::CenterlineGraph& g, int branch) {
  for (const auto& t : g.targets)
    if (t.branch == branch) return t.id;
  return -1;
}

struct Setup {
  gw::Anatomy anatomy;
  gw::Course course;
};

Setup make(double parent_r, double angle_deg, gw::TaskScale scale) {
  const gw::CenterlineGraph g = wide_t(parent_r, angle_deg);
  Setup s{gw::make_anatomy("wide_t", g, nullptr), {}};
  gw::TaskConfig config;
  config.task_scale = scale;
  s.course = gw::make_course(s.anatomy.graph, s.anatomy.branch_lines, target_on(g, 1), config);
  return s;
}

int verdict(const Setup& s, const Vector3d& tip) {
  const double to_course = gw::project_onto_polyline(s.course.line, tip).distance;
  return gw::wrong_branch_entered(gw::TaskConfig{}, s.anatomy, s.course, tip, to_course);
}

}  // namespace

TEST_CASE("radius profile interpolates along the arc and clamps at the ends", "[task][task_scale]") {
  const gw::RadiusProfile p = gw::make_radius_profile({Vector3d(0, 0, 0), Vector3d(0, 0, 0), Vector3d(2, 0, 0),
                                                       Vector3d(2, 3, 0)},
                                                      {1.0, 1.0, 3.0, 6.0});
  REQUIRE(p.arc == std::vector<double>{0.0, 0.0, 2.0, 5.0});
  CHECK(gw::radius_at(p, -1.0) == 1.0);
  CHECK(gw::radius_at(p, 1.0) == Approx(2.0));
  CHECK(gw::radius_at(p, 3.5) == Approx(4.5));
  CHECK(gw::radius_at(p, 9.0) == 6.0);
  CHECK_THROWS_WITH(gw::make_radius_profile({Vector3d::Zero()}, {1.0, 2.0}), Catch::Contains("1 points but 2 radii"));
}

TEST_CASE("a wrong child's ostium is where its centreline leaves the parent's lumen", "[task][task_scale]") {
  // Child at angle a from the course: distance from the course = s sin a, so it leaves a lumen of radius R
  // at s = R / sin a (exact: the crossing is linear between the 1 mm points).
  for (double angle : {90.0, 45.0, 30.0}) {
    const Setup s = make(11.0, angle, gw::TaskScale::kVessel);
    REQUIRE(s.course.vessel_scale);
    REQUIRE(s.course.bifurcations.size() == 1);
    const gw::CourseBifurcation& b = s.course.bifurcations[0];
    REQUIRE(b.wrong_lumens.size() == 1);
    CHECK(b.wrong_lumens[0].ostium_arc == Approx(11.0 / std::sin(angle * 3.14159265358979323846 / 180.0)).margin(1e-6));
    CHECK(b.parent_radius == Approx(11.0));
    CHECK(b.control_radius == Approx(gw::TaskConfig{}.control_radius_mm + 11.0));
  }
}

TEST_CASE("the vessel scale's wrong-branch verdict needs the tip inside the child past its ostium", "[task][task_scale]") {
  const Setup fixed = make(11.0, 90.0, gw::TaskScale::kFixed);
  const Setup vessel = make(11.0, 90.0, gw::TaskScale::kVessel);
  REQUIRE_FALSE(fixed.course.vessel_scale);
  // On the aorta's wall beside the ostium, 8 mm along the child's centreline (which runs inside the aorta):
  // the paper's 4 mm depth calls it the wrong branch; from the walls it is still in the aorta.
  const Vector3d on_wall(8.0, 61.0, 0.0);
  CHECK(verdict(fixed, on_wall) == 0);
  CHECK(verdict(vessel, on_wall) == -1);
  // Just past the ostium (11 mm) but less than the depth beyond it: not yet.
  CHECK(verdict(vessel, Vector3d(13.0, 60.5, 0.0)) == -1);
  // Depth past the ostium, inside the child's 5 mm lumen: entered, for both.
  const Vector3d inside(15.5, 62.0, 0.0);
  CHECK(verdict(vessel, inside) == 0);
  CHECK(verdict(fixed, inside) == 0);
  // Beyond the child's radius from its centreline (and nearer it than the course): outside its lumen.
  CHECK(verdict(vessel, Vector3d(20.0, 66.0, 0.0)) == -1);
  CHECK(verdict(fixed, Vector3d(20.0, 66.0, 0.0)) == 0);
  // Control zone: the fixed 20 mm around the centre, grown by the parent's radius.
  CHECK(fixed.course.bifurcations[0].control_radius == gw::TaskConfig{}.control_radius_mm);
}

TEST_CASE("auto task scale: vessel rules above the wide-vessel radius, the paper's below", "[task][task_scale]") {
  CHECK(make(11.0, 60.0, gw::TaskScale::kAuto).course.vessel_scale);
  const Setup coronary = make(2.0, 60.0, gw::TaskScale::kAuto);
  CHECK_FALSE(coronary.course.vessel_scale);
  CHECK(coronary.course.bifurcations[0].wrong_lumens.empty());
  CHECK(coronary.course.bifurcations[0].control_radius == gw::TaskConfig{}.control_radius_mm);
  gw::TaskConfig bad;
  bad.wide_vessel_radius_mm = 0.0;
  CHECK_THROWS_WITH(gw::check_task_config(bad), Catch::Contains("wide_vessel_radius_mm"));
  CHECK(gw::parse_task_scale("vessel") == gw::TaskScale::kVessel);
  CHECK_THROWS_WITH(gw::parse_task_scale("huge"), Catch::Contains("fixed, vessel, auto"));
}
