// Analytic validation of the Timoshenko beam: energy gradient, cantilever deflection (bending and
// shear-dominated), pure end moment -> circle, rest curvature of the tip, torque transmission.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "engine/wire/beam_element.hpp"
#include "engine/wire/so3.hpp"
#include "engine/wire/wire_queries.hpp"
#include "mechanics_helpers.hpp"

using namespace gw;
using gw::test::settle;
using gw::test::uniform_beam_params;

namespace {

// Clamped at the inlet: with `inserted` equal to a node's arc, that node sits exactly at the inlet.
struct Cantilever {
  WireModel model;
  WireState state;
};

Cantilever cantilever(const WireParams& p, double length) {
  Cantilever c{make_wire_model(p, 0.01), {}};
  c.state = make_initial_state(c.model, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, length);
  return c;
}

double timoshenko_tip_deflection(const WireModel& m, double load, double length) {
  const Vec6& k = m.stiffness.back();
  return load * length * length * length / (3.0 * k[4]) + load * length / k[1];
}

}  // namespace

TEST_CASE("element forces are the exact gradient of the element energy", "[beam]") {
  WireParams p = default_wire_params();
  const WireModel m = make_wire_model(p, 0.01);
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0, 1);
  for (int e : {0, m.elements() - 1}) {  // a body element and a curved tip element
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::Vector3d xa(g(rng), g(rng), g(rng));
      const Mat3 ra = so3_exp(Vec3(g(rng), g(rng), g(rng)));
      const Mat3 rb = ra * so3_exp(m.rest_phi[e] + 0.3 * Vec3(g(rng), g(rng), g(rng)));
      const Eigen::Vector3d xb = xa + ra * Vec3(m.length[e], 0.1 * g(rng), 0.1 * g(rng));
      BeamElementEval ev;
      eval_beam_element(m, e, xa, ra, xb, rb, ev);
      const Vec12 grad = m.length[e] * ev.jac.transpose() * m.stiffness[e].cwiseProduct(ev.strain);
      for (int d = 0; d < 12; ++d) {
        const double h = 1e-6;
        auto energy = [&](double s) {
          Eigen::Vector3d xa2 = xa, xb2 = xb;
          Mat3 ra2 = ra, rb2 = rb;
          Vec3 dir = Vec3::Zero();
          dir[d % 3] = s;
          if (d < 3) xa2 += dir;
          else if (d < 6) ra2 = so3_exp(dir) * ra;
          else if (d < 9) xb2 += dir;
          else rb2 = so3_exp(dir) * rb;
          BeamElementEval e2;
          eval_beam_element(m, e, xa2, ra2, xb2, rb2, e2);
          return e2.energy;
        };
        const double fd = (energy(h) - energy(-h)) / (2 * h);
        INFO("element " << e << " dof " << d);
        CHECK(grad[d] == Approx(fd).epsilon(1e-5).margin(1e-6 * grad.norm()));
      }
    }
  }
}

TEST_CASE("cantilever with a tip load deflects as Timoshenko theory predicts (bending dominated)", "[beam][analytic]") {
  // 40 mm of the real wire (EI = 4.7e4 mN mm^2), 1 mm elements, small load: linear regime.
  Cantilever c = cantilever(uniform_beam_params(60, 1.0), 40.0);
  const int k = first_free_node(c.model, c.state);
  REQUIRE(c.model.arc_from_tip[k - 1] == Approx(40.0));
  REQUIRE(c.state.x[k - 1].norm() < 1e-12);  // the clamp is exactly at the inlet
  const double load = 0.05;  // mN
  c.state.external_force.back() = Eigen::Vector3d(0, load, 0);
  REQUIRE(settle(c.model, c.state, 2000) > 0);
  const double expected = timoshenko_tip_deflection(c.model, load, 40.0);
  const double shear_part = load * 40.0 / c.model.stiffness.back()[1];
  INFO("tip deflection " << c.state.x.back().y() << " expected " << expected << " (shear part " << shear_part << ")");
  CHECK(c.state.x.back().y() == Approx(expected).epsilon(0.01));
  CHECK(c.state.x.back().x() == Approx(40.0).epsilon(1e-4));
}

TEST_CASE("cantilever with a tip load: shear-dominated Timoshenko beam", "[beam][analytic]") {
  // Shear compliance L / kGA made 5x the bending compliance L^3 / 3EI by a low shear coefficient
  // (a beam with a soft core); an Euler-Bernoulli model would be off by a factor ~6.
  WireParams p = uniform_beam_params(20, 0.25);
  p.shear_coefficient = 5e-5;
  Cantilever c = cantilever(p, 10.0);
  const Vec6& ks = c.model.stiffness.back();
  const double bend = 1000.0 / (3.0 * ks[4]), shear = 10.0 / ks[1];
  REQUIRE(shear > 4 * bend);
  const double load = 0.1;
  c.state.external_force.back() = Eigen::Vector3d(0, 0, load);
  REQUIRE(settle(c.model, c.state, 2000) > 0);
  const double expected = timoshenko_tip_deflection(c.model, load, 10.0);
  INFO("tip deflection " << c.state.x.back().z() << " expected " << expected << " (Euler-Bernoulli " << load * bend << ")");
  CHECK(c.state.x.back().z() == Approx(expected).epsilon(0.01));
}

TEST_CASE("a pure end moment bends the beam into a circle of radius EI/M", "[beam][analytic]") {
  const double length = 30.0;
  Cantilever c = cantilever(uniform_beam_params(40, 0.5), length);
  const double ei = c.model.stiffness.back()[4];
  const double moment = 2.0 * M_PI * ei / length;  // closes the beam into one full circle
  const double radius = ei / moment;
  // Ramp the moment up: one linearisation per step, so large rotations are reached gradually.
  const int ramp = 200;
  for (int s = 1; s <= ramp; ++s) {
    c.state.external_torque.back() = Eigen::Vector3d(0, 0, moment * s / ramp);
    REQUIRE(step(c.model, nullptr, Control{}, c.state).ok);
  }
  REQUIRE(settle(c.model, c.state, 5000, 1e-6) > 0);
  const Eigen::Vector3d centre(0, radius, 0);  // clamp at the origin, tangent +x, bending towards +y
  const int k = first_free_node(c.model, c.state);
  double worst = 0;
  for (int i = k; i < c.model.nodes; ++i) worst = std::max(worst, std::abs((c.state.x[i] - centre).norm() - radius));
  INFO("radius " << radius << " mm, worst radial error " << worst << " mm, tip " << c.state.x.back().transpose());
  CHECK(worst < 0.01 * radius);
  CHECK(c.state.x.back().norm() < 0.01 * radius);  // the circle closes at the clamp
}

TEST_CASE("a straightened tip springs back to its rest curvature 0.2/mm", "[beam][analytic]") {
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  WireState s = make_initial_state(m, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.0, 20.0);
  // Straighten everything that is inserted.
  const int k = first_free_node(m, s);
  for (int i = k; i < m.nodes; ++i) {
    s.x[i] = s.inlet + (s.inserted_length_mm - m.arc_from_tip[i]) * s.direction;
    s.q[i] = introducer_frame(s);
  }
  REQUIRE(tip_curvature_vector(m, s).norm() < 1e-9);
  REQUIRE(settle(m, s, 3000, 1e-8) > 0);
  // Curvature of the circle through three nodes of the 6 mm tip (first, middle, last).
  int first = m.nodes - 1;
  while (m.arc_from_tip[first - 1] <= m.params.tip_length_mm + 1e-9) --first;
  const Eigen::Vector3d a = s.x[first], b = s.x[(first + m.nodes - 1) / 2], c = s.x[m.nodes - 1];
  const double kappa = 2.0 * (b - a).cross(c - a).norm() / ((b - a).norm() * (c - b).norm() * (c - a).norm());
  INFO("geometric tip curvature " << kappa);
  CHECK(kappa == Approx(0.2).epsilon(0.01));
  CHECK(tip_curvature_vector(m, s).norm() == Approx(0.2).epsilon(0.01));
  // It bends in the introducer's x-y plane (roll 0): the bending axis t x k is the frame's +z.
  const Eigen::Vector3d z = introducer_frame(s) * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d t = tip_tangents(m, s, 1, 0.0)[0];
  CHECK(t.cross(tip_curvature_vector(m, s)).normalized().dot(z) > 0.9999);
}

TEST_CASE("rotating the proximal end turns the tip by the same angle at rest", "[beam][analytic]") {
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  for (double angle : {M_PI / 2, 2.5}) {
    WireState s = make_initial_state(m, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, 60.0);
    // Bending axis of the tip (t x k): at rest it is the introducer's z axis rolled about the inlet axis.
    auto axis = [&] { return tip_tangents(m, s, 1, 0.0)[0].cross(tip_curvature_vector(m, s)); };
    const Eigen::Vector3d k0 = axis();
    const int steps = 100;
    const Control spin{0.0, angle / (steps * m.dt)};
    for (int i = 0; i < steps; ++i) REQUIRE(step(m, nullptr, spin, s).ok);
    REQUIRE(settle(m, s, 3000, 1e-8) > 0);
    const Eigen::Vector3d k1 = axis();
    // Angle of k1 relative to k0 about the inlet axis (x).
    const double turned = std::atan2(k0.cross(k1).dot(Eigen::Vector3d::UnitX()), k0.dot(k1));
    INFO("commanded " << angle << " rad, tip turned " << turned << " rad");
    CHECK(turned == Approx(angle).margin(0.01));
    CHECK(k1.norm() == Approx(0.2).epsilon(0.01));
  }
}
