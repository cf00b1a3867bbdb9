// Geometry of the navigation task on hand-made centerlines: polyline queries, courses
// (bifurcation directions, goals), omega, reward (Eq. 3), observation layout.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>

#include "task/course.hpp"
#include "task/observation.hpp"
#include "task/polyline.hpp"
#include "task/reward.hpp"
#include "tests/task/hand_made_graphs.hpp"

using Approx = Catch::Detail::Approx;
using Eigen::Vector3d;

TEST_CASE("polyline: arc length, projection, point and tangent", "[task]") {
  const gw::Polyline line = gw::make_polyline({{0, 0, 0}, {10, 0, 0}, {10, 0, 0}, {10, 10, 0}});
  REQUIRE(line.points.size() == 3);  // duplicate dropped
  CHECK(line.length == Approx(20.0));
  const gw::PolylineProjection p = gw::project_onto_polyline(line, {4, 3, 0});
  CHECK(p.arc == Approx(4.0));
  CHECK(p.distance == Approx(3.0));
  CHECK(p.segment == 0);
  const gw::PolylineProjection q = gw::project_onto_polyline(line, {12, 7, 0});
  CHECK(q.arc == Approx(17.0));
  CHECK(q.distance == Approx(2.0));
  CHECK(gw::project_onto_polyline(line, {-5, 0, 0}).arc == Approx(0.0));    // clamped
  CHECK(gw::project_onto_polyline(line, {10, 30, 0}).arc == Approx(20.0));  // clamped
  CHECK((gw::polyline_point(line, 15.0) - Vector3d(10, 5, 0)).norm() < 1e-12);
  CHECK((gw::polyline_tangent(line, 0.0) - Vector3d(1, 0, 0)).norm() < 1e-12);
  CHECK((gw::polyline_tangent(line, 20.0) - Vector3d(0, 1, 0)).norm() < 1e-12);
  // Between point tangents: interpolated, unit.
  CHECK(gw::polyline_tangent(line, 5.0).norm() == Approx(1.0));
  CHECK(gw::polyline_tangent(line, 5.0).y() > 0.0);
  // At the corner the central-difference tangent is the bisector.
  CHECK((gw::polyline_tangent(line, 10.0) - Vector3d(1, 1, 0).normalized()).norm() < 1e-12);
  // A restricted search ignores the first segment.
  CHECK(gw::project_onto_polyline(line, {4, 3, 0}, 1).arc == Approx(13.0));
}

TEST_CASE("polyline: bad input is refused", "[task]") {
  CHECK_THROWS_WITH(gw::make_polyline({{1, 1, 1}}), Catch::Contains("two distinct points"));
  CHECK_THROWS_WITH(gw::make_polyline({{1, 1, 1}, {1, 1, 1}}), Catch::Contains("two distinct points"));
  CHECK_THROWS_WITH(gw::make_polyline({{0, 0, 0}, {NAN, 0, 0}}), Catch::Contains("non-finite"));
}

TEST_CASE("course through a Y bifurcation: directions, goals, control mode", "[task]") {
  const gw::CenterlineGraph g = gwtest::y_graph();
  std::vector<gw::Polyline> lines;
  for (const auto& b : g.branches) lines.push_back(gw::make_polyline(b.points));
  gw::TaskConfig config;
  config.observation.omega_plane = gw::OmegaPlane::kCorrectBranch;  // the paper's omega (approach plane: next test)
  // Target numbering: both leaves have the same length, tie broken by x: (-) first.
  const gw::Course c1 = gw::make_course(g, lines, 1, config);
  const gw::Course c2 = gw::make_course(g, lines, 2, config);
  REQUIRE(c1.bifurcations.size() == 1);
  CHECK(c1.bifurcations[0].arc == Approx(40.0));
  CHECK(c1.line.length == Approx(40.0 + 30.0 * std::sqrt(2.0)).epsilon(1e-9));
  CHECK(c1.goal_arc.size() == 1);  // single bifurcation: the goal is the target itself
  CHECK(c1.goal_arc[0] == Approx(c1.line.length));
  CHECK(c1.policy_always);
  // Correct direction of target 1 is the (-x, +y) child; the wrong one projected on the plane
  // normal to it points along +x+y rotated: w_p is orthogonal to c and unit.
  const auto& b1 = c1.bifurcations[0];
  CHECK((b1.correct_direction - Vector3d(-1, 1, 0).normalized()).norm() < 1e-9);
  REQUIRE(b1.wrong_in_plane.size() == 1);
  CHECK(std::abs(b1.wrong_in_plane[0].dot(b1.correct_direction)) < 1e-12);
  CHECK(b1.wrong_in_plane[0].norm() == Approx(1.0));
  CHECK((b1.wrong_in_plane[0] - Vector3d(1, 1, 0).normalized()).norm() < 1e-9);
  CHECK((c2.bifurcations[0].correct_direction - Vector3d(1, 1, 0).normalized()).norm() < 1e-9);
  CHECK_THROWS_WITH(gw::make_course(g, lines, 3, config), Catch::Contains("valid targets are 1..2"));
}

// The steep-branch case: target 2 of the T graph leaves at 90 degrees. In the paper's plane (normal to
// c = +x) the wrong direction w = +y is the approach axis itself, and the tip's bend, normal to the
// approach, is orthogonal to it whatever the roll: omega cannot tell a tip aimed into the branch from one
// aimed away. In the approach plane (normal to p = +y), w - c = (-1, 1, 0) projects to -x: a tip bent
// towards the side branch reads -1, away from it +1.
TEST_CASE("omega's approach plane sees a 90-degree side branch, the paper's plane does not", "[task]") {
  const gw::CenterlineGraph g = gwtest::t_graph();
  std::vector<gw::Polyline> lines;
  for (const auto& b : g.branches) lines.push_back(gw::make_polyline(b.points));
  const int side = g.targets[0].branch == 2 ? 1 : 2;  // target id of the side branch
  const double rest = 0.2;
  const Vector3d bend_into(0.2, 0, 0), bend_away(-0.2, 0, 0), bend_across(0, 0, 0.2);

  gw::TaskConfig paper;
  paper.observation.omega_plane = gw::OmegaPlane::kCorrectBranch;
  const gw::CourseBifurcation bp = gw::make_course(g, lines, side, paper).bifurcations.at(0);
  CHECK((bp.correct_direction - Vector3d(1, 0, 0)).norm() < 1e-9);
  REQUIRE(bp.wrong_in_plane.size() == 1);
  for (const Vector3d& k : {bend_into, bend_away, bend_across})
    CHECK(gw::wrong_branch_alignment(k, bp.omega_normal, bp.wrong_in_plane[0], rest) == Approx(0.0).margin(1e-9));

  gw::TaskConfig approach;
  approach.observation.omega_plane = gw::OmegaPlane::kApproach;
  const gw::CourseBifurcation ba = gw::make_course(g, lines, side, approach).bifurcations.at(0);
  CHECK((ba.approach_direction - Vector3d(0, 1, 0)).norm() < 1e-9);
  CHECK((ba.omega_normal - ba.approach_direction).norm() < 1e-12);
  CHECK((ba.wrong_in_plane.at(0) - Vector3d(-1, 0, 0)).norm() < 1e-9);
  CHECK(gw::wrong_branch_alignment(bend_into, ba.omega_normal, ba.wrong_in_plane[0], rest) == Approx(-1.0));
  CHECK(gw::wrong_branch_alignment(bend_away, ba.omega_normal, ba.wrong_in_plane[0], rest) == Approx(1.0));
  CHECK(gw::wrong_branch_alignment(bend_across, ba.omega_normal, ba.wrong_in_plane[0], rest) == Approx(0.0).margin(1e-12));

  // Going straight on (target of child 1), the wrong branch is the side one: both planes agree, +x.
  const int straight = 3 - side;
  const gw::CourseBifurcation sp = gw::make_course(g, lines, straight, paper).bifurcations.at(0);
  const gw::CourseBifurcation sa = gw::make_course(g, lines, straight, approach).bifurcations.at(0);
  CHECK((sp.wrong_in_plane.at(0) - Vector3d(1, 0, 0)).norm() < 1e-9);
  CHECK((sa.wrong_in_plane.at(0) - Vector3d(1, 0, 0)).norm() < 1e-9);

  // On the symmetric Y both planes give the same reading up to the in-plane tilt of c.
  const gw::CenterlineGraph y = gwtest::y_graph();
  std::vector<gw::Polyline> ylines;
  for (const auto& b : y.branches) ylines.push_back(gw::make_polyline(b.points));
  const gw::CourseBifurcation ya = gw::make_course(y, ylines, 1, approach).bifurcations.at(0);
  CHECK((ya.wrong_in_plane.at(0) - Vector3d(1, 0, 0)).norm() < 1e-9);  // from the (-x) child to the (+x) one
}

TEST_CASE("course through a tree: one intermediate goal per bifurcation", "[task]") {
  const gw::CenterlineGraph g = gwtest::two_level_tree();
  std::vector<gw::Polyline> lines;
  for (const auto& b : g.branches) lines.push_back(gw::make_polyline(b.points));
  gw::TaskConfig config;
  for (const auto& t : g.targets) {
    const gw::Course c = gw::make_course(g, lines, t.id, config);
    CHECK(c.goal_arc.size() == c.bifurcations.size());
    CHECK(c.goal_arc.back() == Approx(c.line.length));
    REQUIRE(c.lambda_arc.size() == c.goal_arc.size());
    CHECK(c.lambda_arc.back() == Approx(c.line.length));  // the final target
    if (c.bifurcations.size() == 2) {
      CHECK_FALSE(c.policy_always);  // auto: trees hand control only near bifurcations
      CHECK(c.goal_arc[0] == Approx(c.bifurcations[0].arc + config.control_radius_mm));
      // lambda runs to the intermediate target past the hand-over, capped at the final target
      CHECK(c.lambda_arc[0] ==
            Approx(std::min(c.bifurcations[0].arc + config.intermediate_target_mm, c.line.length)));
      CHECK(c.lambda_arc[0] > c.goal_arc[0]);
      gw::TaskConfig at_hand_over = config;
      at_hand_over.intermediate_target_mm = 0;
      CHECK(gw::make_course(g, lines, t.id, at_hand_over).lambda_arc[0] == Approx(c.goal_arc[0]));
      gw::TaskConfig short_target = config;
      short_target.intermediate_target_mm = 5;  // never before the hand-over point
      CHECK(gw::make_course(g, lines, t.id, short_target).lambda_arc[0] == Approx(c.goal_arc[0]));
    }
  }
  config.control_mode = gw::ControlMode::kAlways;
  CHECK(gw::make_course(g, lines, g.targets.back().id, config).policy_always);
}

TEST_CASE("omega: cosine of tip bend vs wrong branch in the plane normal to the correct branch", "[task]") {
  const Vector3d c(0, 0, 1), wp(1, 0, 0);
  const double kappa = 0.2;
  CHECK(gw::wrong_branch_alignment({0.2, 0, 0}, c, wp, kappa) == Approx(1.0));
  CHECK(gw::wrong_branch_alignment({-0.2, 0, 0}, c, wp, kappa) == Approx(-1.0));
  CHECK(gw::wrong_branch_alignment({0, 0.2, 0.5}, c, wp, kappa) == Approx(0.0).margin(1e-12));
  CHECK(gw::wrong_branch_alignment({0.1, 0.1, 0.3}, c, wp, kappa) == Approx(std::sqrt(0.5)));
  // A tip straightened to a quarter of its rest curvature counts only half.
  CHECK(gw::wrong_branch_alignment({0.05, 0, 0}, c, wp, kappa) == Approx(0.5));
  CHECK(gw::wrong_branch_alignment({0, 0, 0}, c, wp, kappa) == Approx(0.0));
  CHECK(gw::wrong_branch_alignment({0.2, 0, 0}, c, Vector3d::Zero(), kappa) == Approx(0.0));
}

TEST_CASE("omega_side: the sine to omega's cosine, so a roll about the plane normal walks a circle", "[task]") {
  const Vector3d n(0, 0, 1), wp(1, 0, 0);
  const double kappa = 0.2;
  CHECK(gw::wrong_branch_side({0.2, 0, 0}, n, wp, kappa) == Approx(0.0).margin(1e-12));
  CHECK(gw::wrong_branch_side({0, 0.2, 0}, n, wp, kappa) == Approx(1.0));   // n x w_p = +y
  CHECK(gw::wrong_branch_side({0, -0.2, 0.7}, n, wp, kappa) == Approx(-1.0));  // the part along n is ignored
  CHECK(gw::wrong_branch_side({0, 0.05, 0}, n, wp, kappa) == Approx(0.5));  // faded like omega
  CHECK(gw::wrong_branch_side({0, 0.2, 0}, n, Vector3d::Zero(), kappa) == Approx(0.0));
  // Rolling the bend by phi about n (what a proximal rotation does to a tip pointing along n) moves
  // atan2(side, omega) by phi, whichever way the wrong branch lies: the sign says which way to turn.
  for (const Vector3d& w : {Vector3d(1, 0, 0), Vector3d(-0.6, 0.8, 0), Vector3d(0, -1, 0)}) {
    const Vector3d k0 = 0.2 * Vector3d(0.8, 0.6, 0);
    double previous = std::atan2(gw::wrong_branch_side(k0, n, w, kappa), gw::wrong_branch_alignment(k0, n, w, kappa));
    for (int step = 1; step <= 8; ++step) {
      const Vector3d k = Eigen::AngleAxisd(0.3 * step, n) * k0;
      const double angle = std::atan2(gw::wrong_branch_side(k, n, w, kappa), gw::wrong_branch_alignment(k, n, w, kappa));
      CHECK(std::remainder(angle - previous, 2 * M_PI) == Approx(0.3));
      previous = angle;
    }
  }
}

TEST_CASE("curvature from two tangents of a circular arc", "[task]") {
  // Arc of radius 5 (curvature 0.2) in the xy plane: tangent at arc s is (cos(s/5), sin(s/5), 0),
  // the curvature vector dt/ds points along (-sin, cos), towards the centre.
  const double r = 5.0, s0 = 1.0, ds = 4.0;
  const Vector3d back(std::cos(s0 / r), std::sin(s0 / r), 0), tip(std::cos((s0 + ds) / r), std::sin((s0 + ds) / r), 0);
  const Vector3d k = gw::curvature_from_tangents(tip, back, ds);
  const double mid = (s0 + ds / 2) / r;
  CHECK(k.normalized().dot(Vector3d(-std::sin(mid), std::cos(mid), 0)) == Approx(1.0).epsilon(1e-9));
  CHECK(k.norm() == Approx(2.0 * std::sin(ds / (2 * r)) / ds));  // chord of the tangent circle
}

TEST_CASE("reward is exactly paper Eq. 3", "[task]") {
  auto eq3 = [](double w, double l, double a) {
    return 2.0 / (1.0 + std::exp(5.0 * (w - 0.1))) - 1.0 + 0.5 * (1.0 - l) - 0.2 * std::abs(a);
  };
  for (double w : {-1.0, -0.3, 0.0, 0.1, 0.7, 1.0})
    for (double l : {0.0, 0.4, 1.0, 1.7})
      for (double a : {-1.0, -0.2, 0.0, 0.5, 1.0}) CHECK(gw::navigation_reward(w, l, a) == eq3(w, l, a));
  CHECK(gw::navigation_reward(0.1, 1.0, 0.0) == Approx(0.0).margin(1e-15));  // sigmoid centre
  CHECK(gw::navigation_reward(-1.0, 0.0, 0.0) == Approx(2.0 / (1.0 + std::exp(-5.5)) - 0.5));
  CHECK(gw::RewardShape{}.omega_centre == 0.1);  // the sigmoid's own default is the paper's
  CHECK(gw::RewardShape{}.omega_slope == 5.0);
  CHECK(gw::TaskConfig{}.reward.omega_centre == -0.5);  // the task's is the shipped actors' (reward.hpp says why)
  CHECK(gw::TaskConfig{}.reward.omega_slope == 8.0);
}

TEST_CASE("reward sigmoid can be shifted and steepened", "[task]") {
  const gw::RewardShape steep{-0.5, 8.0};
  CHECK(gw::navigation_reward(-0.5, 1.0, 0.0, steep) == Approx(0.0).margin(1e-15));  // the new centre
  // The point of the deviation: the paper's sigmoid pays little for aiming from omega -0.65 to -0.95,
  // less than two full rotation steps cost (0.4); the steep one pays more than that.
  const double paper_gain = gw::navigation_reward(-0.95, 1.0, 0.0) - gw::navigation_reward(-0.65, 1.0, 0.0);
  const double steep_gain =
      gw::navigation_reward(-0.95, 1.0, 0.0, steep) - gw::navigation_reward(-0.65, 1.0, 0.0, steep);
  CHECK(paper_gain < 0.05);
  CHECK(steep_gain > 0.4);
  CHECK(gw::navigation_reward(1.0, 1.0, 0.0, steep) == Approx(2.0 / (1.0 + std::exp(12.0)) - 1.0));
  gw::TaskConfig config;
  config.reward.omega_slope = 0.0;
  CHECK_THROWS_WITH(gw::check_task_config(config), Catch::Contains("reward.omega_slope"));
}

TEST_CASE("observation layout is fixed and bounded", "[task]") {
  CHECK(gw::kObservationSize == 15);
  CHECK(std::string(gw::TaskConfig{}.observation.name()) == "guidewire-nav/obs/3");  // the shipped actor's
  gw::ObservationLayout layout;
  CHECK(std::string(layout.name()) == "guidewire-nav/obs/3");
  CHECK(layout.size() == 12);
  layout.omega_side = false;  // obs/2 is retired: the approach plane goes with omega's sine
  CHECK_THROWS_WITH(layout.name(), Catch::Contains("obs/3") && Catch::Contains("retired"));
  layout.omega_plane = gw::OmegaPlane::kCorrectBranch;
  CHECK(std::string(layout.name()) == "guidewire-nav/obs/1");
  CHECK(layout.size() == 11);
  layout.omega_plane = gw::OmegaPlane::kApproach;
  layout.omega_side = true;
  layout.push_pull = true;  // the push/pull actor's layout: obs/3 and two entries
  CHECK(std::string(layout.name()) == "guidewire-nav/obs/5");
  CHECK(layout.size() == 14);
  CHECK(gw::ObservationLayout::parse("guidewire-nav/obs/5").push_pull);
  layout.tip_force = true;  // the generalist's layout: obs/5 and the tip's wall force
  CHECK(std::string(layout.name()) == "guidewire-nav/obs/8");
  CHECK(layout.size() == 15);
  layout.push_pull = false;  // not without the push/pull entries
  CHECK_THROWS_WITH(layout.name(), Catch::Contains("obs/8"));
  layout.push_pull = true;
  layout.tip_force = false;
  CHECK_THROWS_WITH(gw::ObservationLayout::parse("guidewire-nav/obs/7"), Catch::Contains("is not one of"));
  layout.omega_side = false;  // not without omega's sine
  CHECK_THROWS_WITH(layout.name(), Catch::Contains("obs/5"));
  layout.omega_side = true;
  layout.push_pull = false;
  layout.omega_plane = gw::OmegaPlane::kCorrectBranch;  // no layout has the sine in the paper's plane
  CHECK_THROWS_WITH(layout.name(), Catch::Contains("approach"));
  for (const char* name : {"guidewire-nav/obs/1", "guidewire-nav/obs/3", "guidewire-nav/obs/4", "guidewire-nav/obs/5",
                           "guidewire-nav/obs/6", "guidewire-nav/obs/8"})
    CHECK(std::string(gw::ObservationLayout::parse(name).name()) == name);
  CHECK_THROWS_WITH(gw::ObservationLayout::parse("guidewire-nav/obs/2"),
                    Catch::Contains("guidewire-nav/obs/1") && Catch::Contains("guidewire-nav/obs/3"));
  CHECK(std::string(gw::observation_names()[gw::obs_index::kOmegaSide]) == "omega_side");
  CHECK(std::string(gw::observation_names()[gw::obs_index::kWrongBranch]) == "wrong_branch");
  CHECK(std::string(gw::observation_names()[gw::obs_index::kTipForce]) == "tip_force");
  CHECK(gw::parse_omega_plane("approach") == gw::OmegaPlane::kApproach);
  CHECK_THROWS_WITH(gw::parse_omega_plane("sideways"), Catch::Contains("correct_branch, approach"));
  CHECK(std::string(gw::observation_names()[gw::obs_index::kOmega]) == "omega");
  CHECK(std::string(gw::observation_names()[gw::obs_index::kSpeed]) == "speed");
  gw::TaskConfig config;
  gw::Observation lo, hi;
  gw::observation_bounds(config, lo, hi);
  for (int i = 0; i < gw::kObservationSize; ++i) CHECK(lo[i] < hi[i]);
  CHECK(hi[gw::obs_index::kLambda] == config.max_lambda_ratio);
}

TEST_CASE("task config is checked", "[task]") {
  gw::TaskConfig c;
  CHECK_NOTHROW(gw::check_task_config(c));
  c.frame_skip = 0;
  CHECK_THROWS_WITH(gw::check_task_config(c), Catch::Contains("frame_skip"));
  c = {};
  c.push_mm_per_s = NAN;
  CHECK_THROWS_WITH(gw::check_task_config(c), Catch::Contains("push_mm_per_s"));
  CHECK(gw::parse_control_mode("near_bifurcation") == gw::ControlMode::kNearBifurcation);
  CHECK_THROWS_WITH(gw::parse_control_mode("sometimes"), Catch::Contains("sometimes"));
}
