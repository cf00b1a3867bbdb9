// Validation against closed-form statics: Euler buckling of a clamped-free column and the twist of a
// straight wire under an end torque. Reference formulas and tolerances are written in each test.
#include <catch2/catch.hpp>
#include <cmath>

#include "engine/wire/so3.hpp"
#include "validation_helpers.hpp"

using namespace gw;
using namespace gw::validation;

namespace {

// Lateral tip deflection of a clamped-free column (free length `length`, 1 mm elements) after a slow
// ramp of an axial compressive dead load P with a lateral imperfection load 1e-4 P, settled with heavy
// mass damping.
double column_deflection(double length, double load, int span) {
  WireParams p = with_free_span(beam_params(length + 10.0, 1.0, 5e-4), span);
  p.damping_mass = 200.0;  // overdamps the soft first mode near the critical load
  p.damping_stiffness = 1e-4;
  const WireModel m = make_wire_model(p, 0.01);
  WireState s = make_initial_state(m, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, length);
  const int ramp = 30, hold = 270;  // 0.3 s ramp, 2.7 s hold
  for (int i = 1; i <= ramp + hold; ++i) {
    const double f = load * std::min(1.0, static_cast<double>(i) / ramp);
    s.external_force.back() = Eigen::Vector3d(-f, 1e-4 * f, 0);
    if (!step(m, nullptr, Control{}, s).ok) return -1;
  }
  return std::abs(s.x.back().y());
}

}  // namespace

TEST_CASE("a clamped-free column buckles at P_cr = pi^2 EI / (4 L^2)", "[validation][statics]") {
  // Reference: Euler's critical load of a column clamped at one end and free at the other,
  // P_cr = pi^2 EI / (4 L^2). Tolerance 3%: the column must stand (tip deflection below 2% of L, the
  // imperfection amplified by 1 / (1 - P / P_cr)) at 0.97 P_cr and be buckled (above 10% of L, the
  // elastica's ~0.9 sqrt(P / P_cr - 1) L) at 1.03 P_cr. The critical load is then located by bisection
  // on "deflection above 5% of L" and reported.
  // Also with adaptive stepping (2 ms sub-steps in free space).
  const double length = 40.0;
  const int span = GENERATE(1, 4);
  const WireModel probe = make_wire_model(beam_params(length + 10.0, 1.0, 5e-4), 0.01);
  const double ei = probe.stiffness.back()[4];
  const double p_cr = M_PI * M_PI * ei / (4.0 * length * length);
  const double below = column_deflection(length, 0.97 * p_cr, span);
  const double above = column_deflection(length, 1.03 * p_cr, span);
  INFO("P_cr " << p_cr << " mN: deflection at 0.97 P_cr " << below << " mm, at 1.03 P_cr " << above << " mm");
  REQUIRE(below >= 0);
  REQUIRE(above >= 0);
  CHECK(below < 0.02 * length);
  CHECK(above > 0.10 * length);
  double lo = 0.9, hi = 1.1;
  for (int i = 0; i < 7; ++i) {
    const double mid = 0.5 * (lo + hi);
    (column_deflection(length, mid * p_cr, span) > 0.05 * length ? hi : lo) = mid;
  }
  WARN("buckling: measured P_cr / theory = " << 0.5 * (lo + hi) << " (+-" << 0.5 * (hi - lo) << ")");
  CHECK(0.5 * (lo + hi) == Approx(1.0).margin(0.03));
}

TEST_CASE("a straight wire twists by phi = T L / (G J) under an end torque", "[validation][statics]") {
  // Reference: Saint-Venant torsion of a circular shaft, phi = T L / (G J), J = pi r^4 / 2. Tolerance 1%.
  // 40 mm free length, end torque giving 0.5 rad (ramped), settled.
  // Also with adaptive stepping (2 ms sub-steps in free space).
  const double length = 40.0;
  const int span = GENERATE(1, 4);
  WireParams p = with_free_span(beam_params(length + 10.0, 1.0, 5e-4), span);
  p.damping_mass = 1.0;
  p.damping_stiffness = 1e-3;
  const WireModel m = make_wire_model(p, 0.01);
  WireState s = make_initial_state(m, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, length);
  const double r = m.radius_mm;
  const double g = p.young_modulus_kpa / (2.0 * (1.0 + p.poisson_ratio));
  const double gj = g * M_PI * r * r * r * r / 2.0;
  const double torque = 0.5 * gj / length;
  for (int i = 1; i <= 2000; ++i) {
    s.external_torque.back() = Eigen::Vector3d(torque * std::min(1.0, i / 50.0), 0, 0);
    REQUIRE(step(m, nullptr, Control{}, s).ok);
  }
  const int clamp = first_free_node(m, s) - 1;
  const Vec3 rel = so3_log(s.q[clamp].toRotationMatrix().transpose() * s.q.back().toRotationMatrix());
  const double expected = torque * length / gj;
  INFO("twist " << rel.transpose() << " expected " << expected);
  WARN("torsion: phi = " << rel.x() << " rad against T L / (G J) = " << expected << " rad ("
                         << 100.0 * (rel.x() / expected - 1) << "%)");
  CHECK(rel.x() == Approx(expected).epsilon(0.01));
  CHECK(rel.tail<2>().norm() < 1e-6);
}
