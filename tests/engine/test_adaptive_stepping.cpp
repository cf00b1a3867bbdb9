// Adaptive stepping (WireParams::max_free_substep_s, issue 62 item 3): long sub-steps in free lumen, the
// contact sub-step wherever the wall is met. The physics tests of tests/validation run at both settings.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "engine/scene/swept_tube_mesh.hpp"
#include "engine/sim/step.hpp"
#include "engine/wire/wire_model.hpp"
#include "engine/wire/wire_queries.hpp"
#include "mechanics_helpers.hpp"

using namespace gw;

namespace {

std::string write_json(const std::string& text) { return test::write_test_file("adaptive_stepping_test.json", text); }

// A tube of radius `radius` along +x for 30 mm, then bending towards +y on a 40 mm radius through 90 degrees.
VesselScene bent_tube(double radius) {
  std::vector<Eigen::Vector3d> c;
  for (int i = 0; i <= 30; ++i) c.emplace_back(i, 0, 0);
  for (int i = 1; i <= 63; ++i) {
    const double a = 0.5 * M_PI * i / 63;
    c.emplace_back(30 + 40 * std::sin(a), 40 * (1 - std::cos(a)), 0);
  }
  Eigen::MatrixX3d m(c.size(), 3);
  for (std::size_t i = 0; i < c.size(); ++i) m.row(i) = c[i].transpose();
  return make_vessel_scene(swept_tube_mesh(m, radius, 32));
}

struct Insertion {
  bool ok = true;
  int long_substeps = 0, split_substeps = 0, contact_steps = 0;
  double max_penetration = 0;
  WireState state;
};

// The wire pushed into the bent tube at 20 mm/s while turning at 1 rad/s, for `steps` steps of 10 ms.
Insertion insert(const WireModel& m, const VesselScene& scene, int steps) {
  Insertion r;
  r.state = make_initial_state(m, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::UnitX(), 0.3, 5.0);
  for (int i = 0; i < steps && r.ok; ++i) {
    const StepReport rep = step(m, &scene, Control{20.0, 1.0}, r.state);
    r.ok = rep.ok;
    r.long_substeps += rep.long_substeps;
    r.split_substeps += rep.split_substeps;
    r.contact_steps += rep.contact_solves > 0 ? 1 : 0;
    r.max_penetration = std::max(r.max_penetration, rep.max_penetration_mm);
  }
  return r;
}

}  // namespace

TEST_CASE("adaptive stepping: off by default, on for the aortic wire, spans a power of two of sub-steps", "[params][adaptive]") {
  CHECK(default_wire_params().max_free_substep_s == 0);
  CHECK(make_wire_model(default_wire_params(), 0.01).free_span == 1);
  const WireParams coronary = load_wire_params(std::string(GW_SOURCE_DIR) + "/engine/wire/coronary_014.json");
  CHECK(make_wire_model(coronary, 0.01).free_span == 1);
  const WireParams aortic = load_wire_params(std::string(GW_SOURCE_DIR) + "/engine/wire/aortic_035_angled.json");
  CHECK(make_wire_model(aortic, 0.01).free_span == 4);  // 2 ms in free lumen, 0.5 ms at the wall
  WireParams p = default_wire_params();
  p.max_free_substep_s = 0.0015;  // rounded down to a power-of-two multiple of 0.5 ms
  CHECK(make_wire_model(p, 0.01).free_span == 2);
  p.max_free_substep_s = 1.0;  // at most 16 sub-steps as one
  CHECK(make_wire_model(p, 0.04).free_span == 16);
  p.max_free_substep_s = 0.0001;  // shorter than the contact sub-step: off
  CHECK(make_wire_model(p, 0.01).free_span == 1);
  CHECK(load_wire_params(write_json("{\"max_free_substep_s\": 0.002}")).max_free_substep_s == 0.002);
  CHECK_THROWS_WITH(load_wire_params(write_json("{\"max_free_substep_s\": -1}")),
                    Catch::Contains("max_free_substep_s"));
}

TEST_CASE("adaptive stepping: in free space the long sub-steps are the integrator at that sub-step, bit for bit",
          "[adaptive]") {
  // A cantilever released from a bent shape and left to vibrate, with no wall: with sub-steps of 0.5 ms
  // and 2 ms in free lumen, after a first step (whose first sub-step is a contact one: a new state's
  // last sub-step counts as one in contact) every step is five sub-steps of 2 ms, as a model whose
  // sub-step is 2 ms takes them.
  WireParams p = test::uniform_beam_params(60.0, 1.0);
  p.max_free_substep_s = 0.002;
  const WireModel adaptive = make_wire_model(p, 0.01);
  WireParams q = p;
  q.max_substep_s = 0.002;
  q.max_free_substep_s = 0;
  const WireModel coarse = make_wire_model(q, 0.01);
  REQUIRE(adaptive.free_span == 4);
  REQUIRE(coarse.substeps == 5);
  WireState a = make_initial_state(adaptive, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, 50.0);
  for (int i = first_free_node(adaptive, a); i < adaptive.nodes; ++i)
    a.x[i].y() += 1e-4 * std::pow(a.x[i].x(), 2);
  a.last_substep_in_contact = false;  // as after a free sub-step
  WireState c = a;
  int long_substeps = 0;
  for (int s = 0; s < 30; ++s) {
    const StepReport ra = step(adaptive, nullptr, Control{5.0, 0.5}, a);
    const StepReport rc = step(coarse, nullptr, Control{5.0, 0.5}, c);
    REQUIRE(ra.ok);
    REQUIRE(rc.ok);
    long_substeps += ra.long_substeps;
  }
  CHECK(long_substeps == 30 * 5);
  for (int i = 0; i < adaptive.nodes; ++i) {
    CHECK((a.x[i] - c.x[i]).norm() == 0.0);
    CHECK((a.v[i] - c.v[i]).norm() == 0.0);
  }
  // And a wire that starts in the plain state takes its first sub-step at 0.5 ms, so it differs.
  WireState fresh = make_initial_state(adaptive, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, 50.0);
  CHECK(step(adaptive, nullptr, Control{5.0, 0.5}, fresh).long_substeps == 5);  // 0.5, 4 x 2, 1, 0.5 ms
}

TEST_CASE("adaptive stepping: a long sub-step that meets the wall is halved to the contact sub-step", "[adaptive][contact]") {
  // The aortic wire pushed and turned through a 5 mm tube that bends: free in the straight part, riding
  // the outer wall of the bend. With long sub-steps in free lumen it takes them until the wall is met,
  // halves them there, solves every contact at 0.5 ms (penetration as without), and ends where the wire
  // stepped at 0.5 ms throughout ends (0.05 mm).
  const VesselScene scene = bent_tube(5.0);
  const WireParams aortic = load_wire_params(std::string(GW_SOURCE_DIR) + "/engine/wire/aortic_035_angled.json");
  WireParams fixed_params = aortic;
  fixed_params.max_free_substep_s = 0;
  const WireModel adaptive = make_wire_model(aortic, 0.01), fixed = make_wire_model(fixed_params, 0.01);
  const int steps = 350;  // 70 mm: through the straight part and half the bend
  const Insertion a = insert(adaptive, scene, steps), f = insert(fixed, scene, steps);
  REQUIRE(a.ok);
  REQUIRE(f.ok);
  const Eigen::Vector3d tip_a = tip_position(adaptive, a.state), tip_f = tip_position(fixed, f.state);
  INFO("long sub-steps " << a.long_substeps << ", halvings " << a.split_substeps << " (fixed " << f.split_substeps
                         << "), steps with contacts " << a.contact_steps << " / " << f.contact_steps
                         << ", penetration " << a.max_penetration << " / " << f.max_penetration << " mm, tips "
                         << tip_a.transpose() << " / " << tip_f.transpose());
  CHECK(f.long_substeps == 0);
  CHECK(a.long_substeps > steps);                 // free lumen: long sub-steps taken
  CHECK(a.split_substeps > f.split_substeps);     // and halved where they met the wall
  CHECK(a.contact_steps > steps / 4);             // the wire did ride the wall
  CHECK(a.max_penetration < f.max_penetration + 0.01);
  CHECK((tip_a - tip_f).norm() < 0.05);
}
