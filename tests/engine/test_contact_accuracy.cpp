// The contact solve's accuracy check (WireModel::reference_contact_solve_every, bench-mechanics
// --contact-accuracy): its error measure on hand-made impulses, and that turning it on leaves the
// trajectory bit for bit as it is while it reports a converged reference.
#include <catch2/catch.hpp>

#include "anatomy_fixture.hpp"
#include "engine/contact/contact_force_error.hpp"
#include "engine/sim/step.hpp"

using namespace gw;

namespace {

// Two contacts on node 1 (its own point and a midpoint it shares with node 2, weights 1/2), wall below.
std::vector<ContactPoint> two_contacts() {
  std::vector<ContactPoint> c(2);
  for (ContactPoint& p : c) {
    p.n = Eigen::Vector3d::UnitZ();
    p.t1 = Eigen::Vector3d::UnitX();
    p.t2 = Eigen::Vector3d::UnitY();
  }
  c[0].node_a = 1;
  c[1].node_a = 1;
  c[1].node_b = 2;
  c[1].wa = c[1].wb = 0.5;
  return c;
}

}  // namespace

TEST_CASE("contact force error: zero for the same impulses, the net force and the peak node force apart", "[contact][accuracy]") {
  const std::vector<ContactPoint> c = two_contacts();
  Eigen::VectorXd ref(6), same(6), moved(6), stronger(6);
  ref << 2, 0.1, 0, 2, 0, 0;
  same = ref;
  const ContactForceError zero = contact_force_error(c, same, ref, 3);
  CHECK(zero.resultant == 0);
  CHECK(zero.peak_node == 0);
  CHECK(zero.distribution == 0);
  // The same net force, carried by the midpoint instead of the node: node forces change, the net does not.
  moved << 1, 0.1, 0, 3, 0, 0;
  const ContactForceError e = contact_force_error(c, moved, ref, 3);
  CHECK(e.resultant == Approx(0).margin(1e-15));
  CHECK(e.distribution == Approx(2.0 / (std::hypot(2, 0.1) + 2)));
  // Node 1 feels 2 + 1 = 3 (reference) and 1 + 1.5 = 2.5 (moved) along n; node 2 feels 1 and 1.5.
  CHECK(e.peak_node == Approx(std::abs(std::hypot(2.5, 0.1) - std::hypot(3, 0.1)) / std::hypot(3, 0.1)));
  // Every impulse 10% stronger: 10% on the net force and on the peak node.
  stronger = 1.1 * ref;
  const ContactForceError s = contact_force_error(c, stronger, ref, 3);
  CHECK(s.resultant == Approx(0.1 * std::hypot(4, 0.1) / (std::hypot(2, 0.1) + 2)));
  CHECK(s.peak_node == Approx(0.1));
  // No reference impulse: nothing to compare, zeros.
  const ContactForceError none = contact_force_error(c, ref, Eigen::VectorXd::Zero(6), 3);
  CHECK(none.resultant == 0);
  CHECK(none.peak_node == 0);
}

TEST_CASE("the contact accuracy check leaves the trajectory bit for bit and reports converged references", "[contact][accuracy]") {
  const test::Anatomy a = test::load_anatomy("train/t3_out_of_plane_steep/t3_out_of_plane_steep");
  const WireModel plain = make_wire_model(default_wire_params(), 0.01);
  WireModel checked = plain;
  checked.reference_contact_solve_every = 3;
  WireState s = make_initial_state(plain, a.inlet, a.direction, 0.0, 2.0), t = s;
  int checks = 0, converged = 0, solves = 0;
  for (int i = 0; i < 250; ++i) {
    const StepReport rp = step(plain, &a.scene, Control{20.0, 0.3}, s);
    const StepReport rc = step(checked, &a.scene, Control{20.0, 0.3}, t);
    REQUIRE(rp.ok);
    REQUIRE(rc.ok);
    REQUIRE(rp.contact_checks.empty());
    REQUIRE(rc.capped_contact_solves == rp.capped_contact_solves);
    solves += rc.contact_solves;
    for (const ContactForceError& e : rc.contact_checks) {
      ++checks;
      converged += e.reference_converged ? 1 : 0;
      REQUIRE(e.resultant >= 0);
      REQUIRE(e.peak_node >= 0);
    }
  }
  for (int i = 0; i < plain.nodes; ++i) {
    REQUIRE((s.x[i] - t.x[i]).norm() == 0.0);
    REQUIRE((s.v[i] - t.v[i]).norm() == 0.0);
  }
  INFO("contact solves " << solves << " checks " << checks << " converged references " << converged);
  CHECK(solves > 1000);                  // the wire rode along the wall
  CHECK(checks > solves / 4);            // about every third sub-step with contacts was checked
  CHECK(converged >= checks * 95 / 100);  // the reference solve does converge
}
