// The two physics settings of issue 38 (engine/wire/wire_params.hpp): friction with a lever arm and
// rotational inertia per axis. Both off by default (the paper's model, the results table's).
#include <catch2/catch.hpp>
#include <fstream>

#include "engine/sim/assemble_system.hpp"
#include "engine/wire/node_rotational_inertia.hpp"
#include "engine/wire/wire_model.hpp"
#include "mechanics_helpers.hpp"

using namespace gw;

namespace {
std::string write_json(const std::string& text) { return test::write_test_file("physics_settings_test.json", text); }
}  // namespace

TEST_CASE("friction torque and per-axis inertia are off by default and load from the wire JSON", "[params]") {
  const WireParams d = default_wire_params();
  CHECK_FALSE(d.friction_torque);
  CHECK_FALSE(d.per_axis_rotational_inertia);
  const WireParams shipped = load_wire_params(std::string(GW_SOURCE_DIR) + "/engine/wire/coronary_014.json");
  CHECK_FALSE(shipped.friction_torque);
  CHECK_FALSE(shipped.per_axis_rotational_inertia);
  const WireParams on = load_wire_params(write_json("{\"friction_torque\": true, \"per_axis_rotational_inertia\": true}"));
  CHECK(on.friction_torque);
  CHECK(on.per_axis_rotational_inertia);
  CHECK_THROWS_WITH(load_wire_params(write_json("{\"friction_torque\": 1}")), Catch::Contains("true or false"));
}

TEST_CASE("per-axis inertia: rho J about the tangent, rho J / 2 about the bending axes", "[params][inertia]") {
  // Reference: a solid circular section has polar moment J = pi r^4 / 2 and I = J / 2 about each
  // diameter; lumped per node, the node's tensor in its frame is rho l diag(J, I, I).
  WireParams p = default_wire_params();
  p.per_axis_rotational_inertia = true;
  const WireModel m = make_wire_model(p, 0.01);
  WireState s = make_initial_state(m, Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3), 0.7, 50.0);
  const int i = m.nodes - 3;
  const Eigen::Matrix3d r = s.q[i].toRotationMatrix();
  const Eigen::Matrix3d local = r.transpose() * node_rotational_inertia(m, i, r) * r;
  const double j = m.rot_inertia[i];
  CHECK(local(0, 0) == Approx(j));
  CHECK(local(1, 1) == Approx(0.5 * j));
  CHECK(local(2, 2) == Approx(0.5 * j));
  CHECK(std::abs(local(0, 1)) + std::abs(local(0, 2)) + std::abs(local(1, 2)) < 1e-12 * j);
  // The assembled system carries it (no damping in the mass scale here: alpha h is added as 1 + h alpha).
  DynamicsSystem sys;
  assemble_system(m, s, 0, 0, m.h, sys);
  const int k = sys.first_free;
  const Eigen::Matrix3d block = sys.a.diag[i - k].block<3, 3>(3, 3);
  // Subtract the element stiffness part by assembling the same state with the isotropic model.
  WireParams iso = p;
  iso.per_axis_rotational_inertia = false;
  DynamicsSystem sys_iso;
  assemble_system(make_wire_model(iso, 0.01), s, 0, 0, m.h, sys_iso);
  const Eigen::Matrix3d diff = block - sys_iso.a.diag[i - k].block<3, 3>(3, 3);
  const double scale = 1.0 + m.h * p.damping_mass;
  CHECK((diff - scale * (node_rotational_inertia(m, i, r) - j * Eigen::Matrix3d::Identity())).norm() < 1e-9 * j);
}
