// Validation of contact with a moving wall (issue 36) against the tube's own analytic motion: a straight
// tube carried at constant velocity takes a wire resting on its floor along (friction axially, the
// floor's push upwards) with no penetration and the relative velocity going to zero; a tube shaken
// sinusoidally holds a floating wire over 10 cycles without penetration or divergence.
// The references (the tube's axis at time t, the wall's velocity) are written here from the motion's
// parameters, independently of the engine's field evaluation; penetration is measured against the
// inscribed polygon of the tube's rings (apothem R cos(pi / segments)), an over-estimate.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "engine/scene/moving_wall.hpp"
#include "validation_helpers.hpp"

using namespace gw;
using namespace gw::validation;

namespace {

const double kGravity = 9810.0;  // mm/s^2
const double kTubeRadius = 1.0;  // mm
const int kSegments = 32;

struct TubeRun {
  bool ok = true;
  std::string problem;
  int steps = 0;
  double engine_penetration = 0;  // the engine's own largest penetration over the sub-steps [mm]
  double penetration = 0;         // against the analytic tube at the end of each step [mm]
  double relative_speed = 0;      // mean |v_node - v_wall| over the free nodes at the end [mm/s]
  double max_speed = 0;           // fastest node over the run [mm/s]
};

// A 30 mm wire (1 mm elements, mu = 0.3) lying on the floor of a straight tube along x, which moves by
// `motion`; `displacement(t)` and `velocity(t)` are the tube's, written by the caller. Node 0 is the
// introducer's (always held): its element has zero stiffness, so the rest of the wire is free.
TubeRun run_tube(const WallMotion& motion, const TriangleMesh& tube, double seconds, bool gravity,
                 const std::function<Eigen::Vector3d(double)>& displacement,
                 const std::function<Eigen::Vector3d(double)>& velocity) {
  const double length = 30.0;
  WireParams p = beam_params(length, 1.0, 5e-4);
  p.friction = 0.3;
  p.inlet_clearance_mm = 0;
  p.damping_stiffness = 1e-4;
  WireModel m = make_wire_model(p, 0.01);
  m.stiffness[0].setZero();
  const VesselScene scene = attach_wall_motion(make_vessel_scene(tube), motion);
  const double r = m.radius_mm;
  WireState s = make_initial_state(m, Eigen::Vector3d(-15, 0, -kTubeRadius * std::cos(M_PI / kSegments) + r + 1e-4),
                                   Eigen::Vector3d::UnitX(), 0.0, length);
  if (gravity)
    for (int i = 1; i < m.nodes; ++i) s.external_force[i] = m.mass[i] * Eigen::Vector3d(0, 0, -kGravity);
  const double apothem = kTubeRadius * std::cos(M_PI / kSegments);
  TubeRun out;
  const int steps = static_cast<int>(std::round(seconds / m.dt));
  for (int k = 0; k < steps; ++k) {
    const StepReport rep = step(m, &scene, Control{}, s);
    ++out.steps;
    out.engine_penetration = std::max(out.engine_penetration, rep.max_penetration_mm);
    if (!rep.ok) {
      out.ok = false;
      out.problem = rep.problem;
      return out;
    }
    const Eigen::Vector3d axis_point = displacement(s.time);  // the axis is the x axis moved by D(t)
    for (int i = 1; i < m.nodes; ++i) {
      const Eigen::Vector3d d = s.x[i] - axis_point;
      out.penetration = std::max(out.penetration, std::hypot(d.y(), d.z()) + r - apothem);
      out.max_speed = std::max(out.max_speed, s.v[i].norm());
    }
  }
  const Eigen::Vector3d vw = velocity(s.time);
  for (int i = 1; i < m.nodes; ++i) out.relative_speed += (s.v[i] - vw).norm() / (m.nodes - 1);
  return out;
}

TriangleMesh straight_tube() {
  Eigen::MatrixX3d c(51, 3);
  for (int i = 0; i < 51; ++i) c.row(i) << -40.0 + 2.0 * i, 0.0, 0.0;
  return swept_tube_mesh(c, kTubeRadius, kSegments);
}

}  // namespace

TEST_CASE("a tube moving at constant velocity carries a resting wire with it, without penetration",
          "[validation][moving_wall]") {
  // Reference: a rigid tube translating at v = (10, 0, 40) mm/s with the wire on its floor under gravity.
  // Friction (mu g = 2943 mm/s^2) brings the wire to the tube's axial speed within ~4 ms and the floor
  // lifts it at 40 mm/s: after 0.4 s every node moves with the tube, |v - v_wall| < 0.01 mm/s (mean),
  // and no node is ever more than 0.05 mm into the wall. Without the wall's velocity in the constraint
  // the floor would lag the wire by ~v h / 0.3 = 0.067 mm; with friction on the absolute velocity the
  // wire would stay behind (relative speed 10 mm/s).
  const TriangleMesh tube = straight_tube();
  const Eigen::Vector3d v(10, 0, 40);
  const WallMotion motion = rigid_wall_motion(tube, v, Eigen::Vector3d::Zero(), 0.0);
  const TubeRun run = run_tube(
      motion, tube, 0.4, true, [&](double t) { return Eigen::Vector3d(v * t); }, [&](double) { return v; });
  INFO("ok " << run.ok << " " << run.problem << " steps " << run.steps << ": penetration " << run.penetration
             << " mm (engine " << run.engine_penetration << "), relative speed " << run.relative_speed << " mm/s");
  REQUIRE(run.ok);
  CHECK(run.penetration <= 0.05);
  CHECK(run.engine_penetration <= 0.05);
  CHECK(run.relative_speed < 0.01);
}

TEST_CASE("a tube shaken sinusoidally holds a floating wire: no penetration over 10 cycles, no divergence",
          "[validation][moving_wall]") {
  // Reference: the tube's axis at A sin(2 pi f t) with A = (1, 2, 2) mm, f = 2.5 Hz (150 bpm): peak
  // wall speed 2 pi f |A| = 47 mm/s, peak acceleration 740 mm/s^2. No gravity: the wire floats and is
  // knocked about by the walls. Over 10 cycles (4 s): every step converges, no node is more than 0.05 mm
  // into the wall, and no node moves faster than 3 times the wall's peak speed (no energy pumped in).
  const TriangleMesh tube = straight_tube();
  const Eigen::Vector3d a(1.0, 2.0, 2.0);
  const double f = 2.5;
  const WallMotion motion = rigid_wall_motion(tube, Eigen::Vector3d::Zero(), a, 60.0 * f);
  const TubeRun run = run_tube(
      motion, tube, 4.0, false, [&](double t) { return Eigen::Vector3d(a * std::sin(2 * M_PI * f * t)); },
      [&](double t) { return Eigen::Vector3d(a * 2 * M_PI * f * std::cos(2 * M_PI * f * t)); });
  const double peak = 2 * M_PI * f * a.norm();
  INFO("ok " << run.ok << " " << run.problem << " steps " << run.steps << ": penetration " << run.penetration
             << " mm (engine " << run.engine_penetration << "), fastest node " << run.max_speed << " mm/s (wall peak "
             << peak << ")");
  REQUIRE(run.ok);
  CHECK(run.steps == 400);
  CHECK(run.penetration <= 0.05);
  CHECK(run.engine_penetration <= 0.05);
  CHECK(run.max_speed < 3 * peak);
}
