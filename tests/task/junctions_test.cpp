// Junctions beyond the two-way fork (issue 41, docs/junctions.md): omega with k wrong branches, closely
// spaced forks aimed at together, and the paper's reading kept where neither occurs.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>

#include "task/bifurcation_omega.hpp"
#include "task/course.hpp"
#include "task/observation.hpp"
#include "tests/task/hand_made_graphs.hpp"

using Approx = Catch::Detail::Approx;
using Eigen::Vector3d;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRest = 0.2;  // tip curvature, 1/mm

// Root along +y (40 mm) into a junction at (0, 40, 0) with one exit per entry of `exits` (unit directions).
gw::CenterlineGraph k_way_graph(const std::vector<Vector3d>& exits) {
  gw::CenterlineGraph g;
  const Vector3d o(0, 0, 0), c(0, 40, 0);
  g.inlet.position = o;
  g.inlet.branch = 0;
  g.inlet.radius = 2.0;
  g.inlet_direction = Vector3d::UnitY();
  g.branches.push_back(gwtest::branch(0, -1, gwtest::segment(o, c)));
  gw::Bifurcation b;
  b.id = 0;
  b.position = c;
  b.parent = 0;
  for (size_t k = 0; k < exits.size(); ++k) {
    const int id = static_cast<int>(k) + 1;
    g.branches.push_back(gwtest::branch(id, 0, gwtest::segment(c, c + 40.0 * exits[k])));
    b.children.push_back(id);
    gw::Terminal t;
    t.position = g.branches.back().points.back();
    t.branch = id;
    t.radius = 2.0;
    g.targets.push_back(t);
  }
  g.bifurcations.push_back(b);
  gw::number_targets(g);
  return g;
}

std::vector<gw::Polyline> lines_of(const gw::CenterlineGraph& g) {
  std::vector<gw::Polyline> lines;
  for (const auto& b : g.branches) lines.push_back(gw::make_polyline(b.points));
  return lines;
}

// Exit at `tilt` from +y, at azimuth `azimuth` about +y (0 = +x, pi/2 = -z... any fixed convention).
Vector3d exit_direction(double tilt, double azimuth) {
  return Vector3d(std::sin(tilt) * std::cos(azimuth), std::cos(tilt), std::sin(tilt) * std::sin(azimuth));
}

// Target id whose terminal lies on branch `branch`.
int target_on(const gw::CenterlineGraph& g, int branch) {
  for (const auto& t : g.targets)
    if (t.branch == branch) return t.id;
  return -1;
}

// Smallest omega over a full roll of a tip bent in the plane normal to +y (the approach direction).
double best_over_roll(const gw::CourseBifurcation& b, gw::JunctionModel model, double* at_azimuth = nullptr) {
  double best = 2.0;
  for (int i = 0; i < 360; ++i) {
    const double a = 2.0 * kPi * i / 360.0;
    const double w = gw::bifurcation_omega(b, kRest * Vector3d(std::cos(a), 0, std::sin(a)), kRest, model).omega;
    if (w < best) {
      best = w;
      if (at_azimuth) *at_azimuth = a;
    }
  }
  return best;
}

}  // namespace

TEST_CASE("a 3-way junction in three azimuths: combined omega reaches -1 aiming at the correct exit, the max cannot",
          "[task][junctions]") {
  const double tilt = 35.0 * kPi / 180.0;
  const gw::CenterlineGraph g =
      k_way_graph({exit_direction(tilt, 0.0), exit_direction(tilt, 2.0 * kPi / 3.0), exit_direction(tilt, 4.0 * kPi / 3.0)});
  const std::vector<gw::Polyline> lines = lines_of(g);
  gw::TaskConfig separate, combined;
  combined.observation.junctions = gw::JunctionModel::kCombined;
  const int target = target_on(g, 1);  // the exit at azimuth 0 (+x)
  const gw::CourseBifurcation bs = gw::make_course(g, lines, target, separate).bifurcations.at(0);
  const gw::CourseBifurcation bc = gw::make_course(g, lines, target, combined).bifurcations.at(0);
  REQUIRE(bs.wrong_in_plane.size() == 2);
  REQUIRE(bc.wrong_in_plane.size() == 2);  // no fork follows: the same directions, read differently

  // Bent towards the correct exit (+x): the max sees both wrong exits 150 degrees off, the mean 180.
  const Vector3d towards = kRest * Vector3d::UnitX();
  CHECK(gw::bifurcation_omega(bs, towards, kRest, gw::JunctionModel::kSeparate).omega ==
        Approx(std::cos(150.0 * kPi / 180.0)).margin(0.02));
  CHECK(gw::bifurcation_omega(bc, towards, kRest, gw::JunctionModel::kCombined).omega == Approx(-1.0).margin(1e-3));
  CHECK(gw::bifurcation_omega(bc, towards, kRest, gw::JunctionModel::kCombined).side == Approx(0.0).margin(1e-3));
  // Over a full roll: the combined reading's best is -1 and lies at the correct exit; the max never
  // gets below -0.87, so a rule or actor that turns until omega is near -1 never stops.
  double azimuth = -1;
  CHECK(best_over_roll(bc, gw::JunctionModel::kCombined, &azimuth) == Approx(-1.0).margin(1e-3));
  CHECK(std::min(azimuth, 2.0 * kPi - azimuth) < 2.0 * kPi / 360.0 + 1e-9);
  CHECK(best_over_roll(bs, gw::JunctionModel::kSeparate) > -0.87);
  // kway reads one k-way junction as combined does: the same directions, the same mean.
  gw::TaskConfig kway;
  kway.observation.junctions = gw::JunctionModel::kKWay;
  const gw::CourseBifurcation bk = gw::make_course(g, lines, target, kway).bifurcations.at(0);
  REQUIRE(bk.wrong_in_plane.size() == 2);
  for (const Vector3d& k3 : {towards, Vector3d(0, 0, kRest), Vector3d(-0.1, 0.05, 0.17)}) {
    const gw::OmegaReading rk = gw::bifurcation_omega(bk, k3, kRest, gw::JunctionModel::kKWay);
    const gw::OmegaReading rc = gw::bifurcation_omega(bc, k3, kRest, gw::JunctionModel::kCombined);
    CHECK(rk.omega == rc.omega);
    CHECK(rk.side == rc.side);
  }
}

TEST_CASE("a planar trifurcation: the side exit aims away from both others, the middle exit reads 0 combined",
          "[task][junctions]") {
  const double tilt = 35.0 * kPi / 180.0;
  const gw::CenterlineGraph g = k_way_graph({exit_direction(tilt, kPi), Vector3d::UnitY(), exit_direction(tilt, 0.0)});
  const std::vector<gw::Polyline> lines = lines_of(g);
  gw::TaskConfig combined;
  combined.observation.junctions = gw::JunctionModel::kCombined;
  // Side exit (-x): both wrong exits lie towards +x, so the best bend is -x, at -1.
  const gw::CourseBifurcation side = gw::make_course(g, lines, target_on(g, 1), combined).bifurcations.at(0);
  CHECK(gw::bifurcation_omega(side, kRest * Vector3d(-1, 0, 0), kRest, gw::JunctionModel::kCombined).omega ==
        Approx(-1.0).margin(1e-6));
  CHECK(gw::bifurcation_omega(side, kRest * Vector3d(1, 0, 0), kRest, gw::JunctionModel::kCombined).omega ==
        Approx(1.0).margin(1e-6));
  // Middle exit: the two wrong directions cancel; no bend is preferred (like a wrong branch along the normal).
  const gw::CourseBifurcation middle = gw::make_course(g, lines, target_on(g, 2), combined).bifurcations.at(0);
  REQUIRE(middle.wrong_in_plane.size() == 2);
  for (const Vector3d& k : {Vector3d(1, 0, 0), Vector3d(0, 0, 1), Vector3d(-0.6, 0, 0.8)}) {
    const gw::OmegaReading r = gw::bifurcation_omega(middle, kRest * k, kRest, gw::JunctionModel::kCombined);
    CHECK(r.omega == Approx(0.0).margin(1e-9));
    CHECK(r.side == Approx(0.0).margin(1e-9));
  }
  // The max reads |cos|: the in-plane bends are the worst, the out-of-plane one 0.
  CHECK(gw::bifurcation_omega(middle, kRest * Vector3d(1, 0, 0), kRest, gw::JunctionModel::kSeparate).omega ==
        Approx(1.0).margin(1e-6));
}

TEST_CASE("kway at a planar trifurcation's middle exit whose side exits are not exactly opposite, as a mesh gives: "
          "the mean points out of their plane and reads -1 there",
          "[task][junctions]") {
  // Side exits 1 degree off one plane: their directions in omega's plane are 179 degrees apart, their mean
  // is short but not zero, and once normalised it is the bisector of the small angle, out of their plane.
  // So kway aims the tip out of the exits' plane (where the extracted t5 pattern lost the middle exit 4 of
  // 6: the held bend slides into a side exit; results/junctions/README.md), it does not read 0 there.
  const double tilt = 35.0 * kPi / 180.0, off = 1.0 * kPi / 180.0;
  const gw::CenterlineGraph g = k_way_graph({exit_direction(tilt, kPi + off), Vector3d::UnitY(), exit_direction(tilt, 0.0)});
  const std::vector<gw::Polyline> lines = lines_of(g);
  gw::TaskConfig kway;
  kway.observation.junctions = gw::JunctionModel::kKWay;
  const gw::CourseBifurcation middle = gw::make_course(g, lines, target_on(g, 2), kway).bifurcations.at(0);
  REQUIRE(middle.wrong_in_plane.size() == 2);
  double azimuth = 0;
  CHECK(best_over_roll(middle, gw::JunctionModel::kKWay, &azimuth) == Approx(-1.0).margin(1e-3));
  CHECK(std::abs(std::sin(azimuth)) > 0.999);  // out of the exits' plane (x-y)
  for (const Vector3d& k : {Vector3d(1, 0, 0), Vector3d(-1, 0, 0)})  // bent at either side exit
    CHECK(std::abs(gw::bifurcation_omega(middle, kRest * k, kRest, gw::JunctionModel::kKWay).omega) < 0.02);
  // The paper's reading there: the most dangerous exit, |cos| of the bend, lowest (0) out of the plane.
  CHECK(best_over_roll(middle, gw::JunctionModel::kSeparate) == Approx(0.0).margin(0.02));
}

TEST_CASE("a two-way fork reads the same with junctions separate and combined", "[task][junctions]") {
  for (const gw::CenterlineGraph& g : {gwtest::y_graph(), gwtest::t_graph(), gwtest::two_level_tree()}) {
    const std::vector<gw::Polyline> lines = lines_of(g);
    gw::TaskConfig separate, combined;
    combined.observation.junctions = gw::JunctionModel::kCombined;
    for (const auto& t : g.targets) {
      const gw::Course cs = gw::make_course(g, lines, t.id, separate), cc = gw::make_course(g, lines, t.id, combined);
      REQUIRE(cs.bifurcations.size() == cc.bifurcations.size());
      for (size_t k = 0; k < cs.bifurcations.size(); ++k) {
        const gw::CourseBifurcation &a = cs.bifurcations[k], &b = cc.bifurcations[k];
        REQUIRE(a.wrong_in_plane.size() == b.wrong_in_plane.size());
        for (size_t i = 0; i < a.wrong_in_plane.size(); ++i) CHECK(a.wrong_in_plane[i] == b.wrong_in_plane[i]);
        for (const Vector3d& k3 : {Vector3d(0.2, 0, 0), Vector3d(0, 0, 0.2), Vector3d(-0.1, 0.05, 0.17)}) {
          const gw::OmegaReading ra = gw::bifurcation_omega(a, k3, kRest, gw::JunctionModel::kSeparate);
          const gw::OmegaReading rb = gw::bifurcation_omega(b, k3, kRest, gw::JunctionModel::kCombined);
          CHECK(ra.omega == rb.omega);  // bit for bit
          CHECK(ra.side == rb.side);
        }
      }
    }
  }
}

TEST_CASE("closely spaced forks: the first fork also aims away from the second's wrong child, only when close",
          "[task][junctions]") {
  // Root along +y to fork A at (0, 40, 0): child 1 leaves towards -x, child 2 goes on along +y for `gap` mm
  // to fork B, whose child 3 leaves towards +z and child 4 goes on. Radius 2 mm: diameter 4 mm.
  auto graph = [](double gap) {
    gw::CenterlineGraph g;
    const Vector3d o(0, 0, 0), a(0, 40, 0), b(0, 40 + gap, 0);
    g.inlet.position = o;
    g.inlet.branch = 0;
    g.inlet.radius = 2.0;
    g.inlet_direction = Vector3d::UnitY();
    g.branches.push_back(gwtest::branch(0, -1, gwtest::segment(o, a)));
    g.branches.push_back(gwtest::branch(1, 0, gwtest::segment(a, a + Vector3d(-25, 25, 0))));
    g.branches.push_back(gwtest::branch(2, 0, gwtest::segment(a, b, 0.5)));
    g.branches.push_back(gwtest::branch(3, 2, gwtest::segment(b, b + Vector3d(0, 25, 25))));
    g.branches.push_back(gwtest::branch(4, 2, gwtest::segment(b, b + Vector3d(0, 40, 0))));
    for (int k = 0; k < 2; ++k) {
      gw::Bifurcation f;
      f.id = k;
      f.position = k == 0 ? a : b;
      f.parent = k == 0 ? 0 : 2;
      f.children = k == 0 ? std::vector<int>{1, 2} : std::vector<int>{3, 4};
      g.bifurcations.push_back(f);
    }
    for (int leaf : {1, 3, 4}) {
      gw::Terminal t;
      t.position = g.branches[static_cast<size_t>(leaf)].points.back();
      t.branch = leaf;
      t.radius = 2.0;
      g.targets.push_back(t);
    }
    gw::number_targets(g);
    return g;
  };
  gw::TaskConfig separate, combined, kway;
  combined.observation.junctions = gw::JunctionModel::kCombined;  // close: under 2 diameters = 8 mm
  kway.observation.junctions = gw::JunctionModel::kKWay;           // close forks apart, as separate
  for (double gap : {5.0, 20.0}) {
    INFO("gap " << gap << " mm");
    const gw::CenterlineGraph g = graph(gap);
    const std::vector<gw::Polyline> lines = lines_of(g);
    const int straight = target_on(g, 4);
    const gw::Course cs = gw::make_course(g, lines, straight, separate), cc = gw::make_course(g, lines, straight, combined);
    REQUIRE(cc.bifurcations.size() == 2);
    CHECK(cs.bifurcations[0].wrong_in_plane.size() == 1);
    CHECK(cc.bifurcations[0].wrong_in_plane.size() == (gap < 8.0 ? 2u : 1u));
    CHECK(cc.bifurcations[1].wrong_in_plane.size() == 1);  // nothing follows the second fork
    // kway keeps each fork to its own wrong child and reads it as separate does, bit for bit.
    const gw::Course ck = gw::make_course(g, lines, straight, kway);
    REQUIRE(ck.bifurcations.size() == 2);
    for (size_t k = 0; k < 2; ++k) {
      REQUIRE(ck.bifurcations[k].wrong_in_plane.size() == 1);
      CHECK(ck.bifurcations[k].wrong_in_plane[0] == cs.bifurcations[k].wrong_in_plane[0]);
      for (const Vector3d& k3 : {Vector3d(0.2, 0, 0), Vector3d(0, 0, 0.2), Vector3d(-0.1, 0.05, 0.17)}) {
        const gw::OmegaReading rk = gw::bifurcation_omega(ck.bifurcations[k], k3, kRest, gw::JunctionModel::kKWay);
        const gw::OmegaReading rs = gw::bifurcation_omega(cs.bifurcations[k], k3, kRest, gw::JunctionModel::kSeparate);
        CHECK(rk.omega == rs.omega);
        CHECK(rk.side == rs.side);
      }
    }
    if (gap < 8.0) {
      // Aiming away from -x only (the first fork alone) points the tip at the second fork's +z child
      // half the time; the combined reading is lowest bent away from both, towards +x -z.
      double azimuth = 0;
      best_over_roll(cc.bifurcations[0], gw::JunctionModel::kCombined, &azimuth);
      CHECK(std::cos(azimuth) > 0.5);
      CHECK(std::sin(azimuth) < -0.5);
    }
  }
}

TEST_CASE("layout obs/4 is obs/3 with combined junctions", "[task][junctions]") {
  gw::ObservationLayout c = gw::ObservationLayout::parse("guidewire-nav/obs/4");
  CHECK(c.junctions == gw::JunctionModel::kCombined);
  CHECK(c.omega_side);
  CHECK(c.omega_plane == gw::OmegaPlane::kApproach);
  CHECK(std::string(c.name()) == "guidewire-nav/obs/4");
  CHECK(c.size() == gw::kSideObservationSize);
  c = gw::ObservationLayout::parse("guidewire-nav/obs/3");
  CHECK(c.junctions == gw::JunctionModel::kSeparate);
  c.omega_side = false;
  c.junctions = gw::JunctionModel::kCombined;  // combined junctions without omega's sine: no such layout
  CHECK_THROWS_WITH(c.name(), Catch::Contains("obs/4"));
  CHECK(gw::parse_junction_model("combined") == gw::JunctionModel::kCombined);
  CHECK_THROWS_WITH(gw::parse_junction_model("merged"), Catch::Contains("separate, combined, kway"));
  // obs/6: obs/3 with k-way junctions read together, close forks apart.
  gw::ObservationLayout k = gw::ObservationLayout::parse("guidewire-nav/obs/6");
  CHECK(k.junctions == gw::JunctionModel::kKWay);
  CHECK(k.omega_side);
  CHECK(k.size() == gw::kSideObservationSize);
  CHECK(std::string(k.name()) == "guidewire-nav/obs/6");
  CHECK(gw::parse_junction_model("kway") == gw::JunctionModel::kKWay);
  CHECK(std::string(gw::junction_model_name(gw::JunctionModel::kKWay)) == "kway");
  k.omega_side = false;
  CHECK_THROWS_WITH(k.name(), Catch::Contains("obs/6"));
  gw::TaskConfig bad;
  bad.close_junction_diameters = -1;
  CHECK_THROWS_WITH(gw::check_task_config(bad), Catch::Contains("close_junction_diameters"));
}
