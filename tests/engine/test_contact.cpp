// Contact with the vessel wall: pushing through committed anatomies (curved tube, bifurcation) without
// penetrating, and steering in a symmetric Y by the proximal roll alone.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "anatomy_fixture.hpp"
#include "mechanics_helpers.hpp"
#include "engine/contact/detect_contacts.hpp"
#include "engine/scene/moving_wall.hpp"
#include "engine/sim/step.hpp"
#include "engine/wire/wire_queries.hpp"

using namespace gw;

namespace {

struct PushResult {
  int steps = 0;
  bool ok = true;
  std::string problem;
  double max_penetration = 0;
  int max_contacts = 0;
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
};

PushResult push_through(const WireModel& m, const test::Anatomy& a, double roll, double push_mm_per_s, double length_mm,
                        double rotate_rad_per_s = 0) {
  WireState s = make_initial_state(m, a.inlet, a.direction, roll, 2.0);
  PushResult r;
  const Control c{push_mm_per_s, rotate_rad_per_s};
  while (s.inserted_length_mm < length_mm) {
    const StepReport rep = step(m, &a.scene, c, s);
    ++r.steps;
    r.max_penetration = std::max(r.max_penetration, rep.max_penetration_mm);
    r.max_contacts = std::max(r.max_contacts, rep.contacts);
    if (!rep.ok) {
      r.ok = false;
      r.problem = rep.problem;
      break;
    }
  }
  r.tip = tip_position(m, s);
  return r;
}

// A closed box [lo, hi] (the lumen inside, outward normals), each face a grid of squares `cell` wide with
// its own vertices (no vertex normal blends two faces: every wall point's normal is its face's).
TriangleMesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double cell) {
  TriangleMesh m;
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  for (int axis = 0; axis < 3; ++axis)
    for (int end = 0; end < 2; ++end) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      const int nu = static_cast<int>(std::ceil((hi[u] - lo[u]) / cell));
      const int nw = static_cast<int>(std::ceil((hi[w] - lo[w]) / cell));
      const int base = static_cast<int>(v.size());
      for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nw; ++j) {
          Eigen::Vector3d p;
          p[axis] = end ? hi[axis] : lo[axis];
          p[u] = lo[u] + (hi[u] - lo[u]) * i / nu;
          p[w] = lo[w] + (hi[w] - lo[w]) * j / nw;
          v.push_back(p);
        }
      for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nw; ++j) {
          const int a = base + i * (nw + 1) + j, b = a + nw + 1, c = b + 1, d = a + 1;
          // (u, w, axis) is right-handed: counter-clockwise in (u, w) faces +axis, outward at the high end.
          if (end) {
            f.emplace_back(a, b, c);
            f.emplace_back(a, c, d);
          } else {
            f.emplace_back(a, c, b);
            f.emplace_back(a, d, c);
          }
        }
    }
  m.V.resize(static_cast<int>(v.size()), 3);
  m.F.resize(static_cast<int>(f.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.V.row(static_cast<int>(i)) = v[i].transpose();
  for (std::size_t i = 0; i < f.size(); ++i) m.F.row(static_cast<int>(i)) = f[i].transpose();
  return m;
}

}  // namespace

TEST_CASE("a point wedged in a crease is held by both walls, a point pressed on one wall by that wall alone", "[contact]") {
  // The box's end cap (x = 4) meets its side wall (y = 1) at a right angle. Node 10 of a straight wire along
  // x is put 0.2 mm from the cap and `depth` into the side wall (the wire's surface beyond it). The same box
  // moving (a rigid drift along x, at rest at t = 0) gives the same contacts with the wall's velocity.
  const TriangleMesh box = box_mesh(Eigen::Vector3d(-20, -1, -1), Eigen::Vector3d(4, 1, 1), 0.1);
  const VesselScene still = make_vessel_scene(box);
  const VesselScene moving =
      attach_wall_motion(still, rigid_wall_motion(box, Eigen::Vector3d(2, 0, 0), Eigen::Vector3d::Zero(), 60));
  const WireModel m = make_wire_model(test::uniform_beam_params(20.0, 1.0), 0.01);
  const int node = 10;
  auto contacts_at = [&](const VesselScene& scene, double depth) {
    WireState s = make_initial_state(m, Eigen::Vector3d(-16, 0, 0), Eigen::Vector3d::UnitX(), 0.0, 20.0);
    const Eigen::Vector3d shift = Eigen::Vector3d(3.8, 1 - m.radius_mm + depth, 0.3) - s.x[node];
    for (Eigen::Vector3d& x : s.x) x += shift;
    std::vector<ContactPoint> out;
    double deepest = 0;
    detect_contacts(m, scene, s, std::vector<Eigen::Vector3d>(m.nodes, Eigen::Vector3d::Zero()), m.h, out, deepest);
    std::vector<ContactPoint> at_node;
    for (const ContactPoint& c : out)
      if (c.point == node) at_node.push_back(c);
    return at_node;
  };
  for (const VesselScene* scene : {&still, &moving}) {
    INFO((scene == &still ? "static wall" : "moving wall"));
    const std::vector<ContactPoint> pressed = contacts_at(*scene, 0.5 * kCreaseDepthMm);
    REQUIRE(pressed.size() == 1);
    CHECK(pressed[0].n.dot(Eigen::Vector3d(0, -1, 0)) > 0.999);
    const std::vector<ContactPoint> wedged = contacts_at(*scene, 2 * kCreaseDepthMm);
    REQUIRE(wedged.size() == 2);
    CHECK(wedged[0].side == 0);
    CHECK(wedged[0].n.dot(Eigen::Vector3d(0, -1, 0)) > 0.999);
    CHECK(wedged[0].gap == Approx(-2 * kCreaseDepthMm).margin(1e-9));
    CHECK(wedged[1].side == 1);
    CHECK(wedged[1].n.dot(Eigen::Vector3d(-1, 0, 0)) > 0.999);
    CHECK(wedged[1].gap == Approx(0.2 - m.radius_mm).margin(1e-9));
    const Eigen::Vector3d drift = scene == &moving ? Eigen::Vector3d(2, 0, 0) : Eigen::Vector3d::Zero();
    CHECK((wedged[1].v_wall - drift).norm() < 1e-9);
  }
}

TEST_CASE("vessel scene: inside is positive, outside negative, inward normal points into the lumen", "[contact]") {
  const test::Anatomy a = test::load_anatomy("train/t1_straight_y/t1_straight_y");
  const WallDistance in = wall_distance(a.scene, Eigen::Vector3d(0, 0, 30));
  CHECK(in.signed_distance == Approx(1.75).epsilon(0.05));
  const WallDistance near = wall_distance(a.scene, Eigen::Vector3d(1.5, 0, 30));
  CHECK(near.signed_distance == Approx(0.25).margin(0.06));
  CHECK(near.inward.dot(Eigen::Vector3d(-1, 0, 0)) > 0.95);
  const WallDistance out = wall_distance(a.scene, Eigen::Vector3d(2.5, 0, 30));
  CHECK(out.signed_distance == Approx(-0.75).margin(0.06));
  CHECK(out.inward.dot(Eigen::Vector3d(-1, 0, 0)) > 0.95);
}

TEST_CASE("re-linearising a contact keeps the wall it started on, never the opposite one", "[contact]") {
  // t1's access vessel: radius 1.75 mm around the z axis. A point pressed on the +x wall whose predicted
  // motion crosses the axis is nearer the -x wall at mid-motion; that wall's normal must not replace
  // the +x one (it would release the point towards the +x wall).
  const test::Anatomy a = test::load_anatomy("train/t1_straight_y/t1_straight_y");
  const WallDistance start = wall_distance(a.scene, Eigen::Vector3d(1.5, 0, 30));
  const WallDistance across = wall_distance(a.scene, Eigen::Vector3d(-0.3, 0, 30));
  const WallDistance along = wall_distance(a.scene, Eigen::Vector3d(1.45, 0.4, 30.3));
  REQUIRE(start.inward.x() < -0.95);
  REQUIRE(across.inward.x() > 0.95);
  CHECK_FALSE(same_wall_side(start.inward, across.inward));
  CHECK(same_wall_side(start.inward, along.inward));
  // The 60 degree boundary itself.
  const Eigen::Vector3d n(1, 0, 0);
  CHECK(same_wall_side(n, Eigen::Vector3d(std::cos(0.9 * M_PI / 3), std::sin(0.9 * M_PI / 3), 0)));
  CHECK_FALSE(same_wall_side(n, Eigen::Vector3d(std::cos(1.1 * M_PI / 3), std::sin(1.1 * M_PI / 3), 0)));
}

TEST_CASE("a vessel mesh oriented inwards is refused", "[contact]") {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;  // outward tetrahedron
  CHECK_NOTHROW(make_vessel_scene(m));
  m.F.col(1).swap(m.F.col(2));
  CHECK_THROWS_WITH(make_vessel_scene(m), Catch::Contains("signed volume"));
  CHECK_THROWS_WITH(make_vessel_scene(TriangleMesh{}), Catch::Contains("empty"));
}

TEST_CASE("steerability: in a symmetric Y the proximal roll alone picks the branch", "[contact][steer]") {
  const test::Anatomy a = test::load_anatomy("train/t1_straight_y/t1_straight_y");
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  // Roll that makes the tip bend towards +x (branch "right"): the introducer frame's +y must map to +x.
  const WireState probe = make_initial_state(m, a.inlet, a.direction, 0.0, 2.0);
  const Eigen::Vector3d y0 = introducer_frame(probe) * Eigen::Vector3d::UnitY();
  const double roll_right = std::atan2(y0.cross(Eigen::Vector3d::UnitX()).dot(a.direction), y0.dot(Eigen::Vector3d::UnitX()));
  const PushResult right = push_through(m, a, roll_right, 20.0, 110.0);
  const PushResult left = push_through(m, a, roll_right + M_PI, 20.0, 110.0);
  INFO("right: ok " << right.ok << " " << right.problem << " tip " << right.tip.transpose() << " pen " << right.max_penetration
                    << " contacts " << right.max_contacts);
  INFO("left: ok " << left.ok << " " << left.problem << " tip " << left.tip.transpose() << " pen " << left.max_penetration
                   << " contacts " << left.max_contacts);
  REQUIRE(right.ok);
  REQUIRE(left.ok);
  CHECK(right.tip.x() > 10.0);
  CHECK(left.tip.x() < -10.0);
  CHECK(right.max_penetration < 0.05);
  CHECK(left.max_penetration < 0.05);
}

TEST_CASE("pushing through a curved, out-of-plane vessel: no penetration beyond 0.05 mm, no NaN", "[contact]") {
  const test::Anatomy a = test::load_anatomy("train/t3_out_of_plane_steep/t3_out_of_plane_steep");
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  const PushResult r = push_through(m, a, 0.0, 20.0, 90.0);
  INFO("ok " << r.ok << " " << r.problem << " tip " << r.tip.transpose() << " max penetration " << r.max_penetration
             << " contacts " << r.max_contacts);
  REQUIRE(r.ok);
  CHECK(r.max_penetration < 0.05);
  CHECK(r.max_contacts > 10);  // the wire really rode along the wall
  CHECK((r.tip - a.inlet).norm() > 50.0);
}

TEST_CASE("a state copied mid-run steps bit-identically to the original", "[contact][determinism]") {
  const test::Anatomy a = test::load_anatomy("train/t1_straight_y/t1_straight_y");
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  WireState s = make_initial_state(m, a.inlet, a.direction, 0.4, 2.0);
  for (int i = 0; i < 150; ++i) REQUIRE(step(m, &a.scene, Control{20.0, 0.5}, s).ok);
  WireState copy = s;
  copy.wall_cache.clear();  // the broad-phase cache is only an accelerator
  for (int i = 0; i < 50; ++i) {
    REQUIRE(step(m, &a.scene, Control{20.0, -0.3}, s).ok);
    REQUIRE(step(m, &a.scene, Control{20.0, -0.3}, copy).ok);
  }
  for (int i = 0; i < m.nodes; ++i) REQUIRE((s.x[i] - copy.x[i]).norm() == 0.0);
}

TEST_CASE("a diverged state is reported and refused until reset", "[contact][divergence]") {
  const test::Anatomy a = test::load_anatomy("train/t1_straight_y/t1_straight_y");
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  WireState s = make_initial_state(m, a.inlet, a.direction, 0.0, 20.0);
  s.x.back() += Eigen::Vector3d(5.0, 0, 0);  // teleport the tip through the wall
  const StepReport r = step(m, &a.scene, Control{}, s);
  CHECK_FALSE(r.ok);
  CHECK_THAT(r.problem, Catch::Contains("outside the vessel wall"));
  const StepReport again = step(m, &a.scene, Control{}, s);
  CHECK_FALSE(again.ok);
  CHECK_THAT(again.problem, Catch::Contains("reset"));
  WireState nan = make_initial_state(m, a.inlet, a.direction, 0.0, 20.0);
  nan.v.back() = Eigen::Vector3d(std::nan(""), 0, 0);
  const StepReport rn = step(m, nullptr, Control{}, nan);
  CHECK_FALSE(rn.ok);
  CHECK_THAT(rn.problem, Catch::Contains("NaN"));
}

TEST_CASE("long run: 100,000 integration sub-steps in and out of the Y without NaN or penetration", "[.long]") {
  const test::Anatomy a = test::load_anatomy("train/t1_straight_y/t1_straight_y");
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  WireState s = make_initial_state(m, a.inlet, a.direction, 0.0, 2.0);
  double worst = 0;
  const int steps = 100000 / m.substeps;
  for (int i = 0; i < steps; ++i) {
    // Push in to ~100 mm and pull back to ~30 mm repeatedly while turning back and forth.
    const double phase = std::fmod(i * m.dt, 10.0);
    const Control c{phase < 5.0 ? 15.0 : -15.0, 1.5 * std::sin(0.7 * i * m.dt)};
    const StepReport r = step(m, &a.scene, c, s);
    INFO("step " << i << ": " << r.problem);
    REQUIRE(r.ok);
    worst = std::max(worst, r.max_penetration_mm);
  }
  INFO("max penetration " << worst);
  CHECK(worst < 0.05);
}
