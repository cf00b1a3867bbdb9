// The contact stage's building blocks against references: the grid range query against FCL's
// sphere-vs-BVH query, and the projected Gauss-Seidel solve (lazily built W, contact velocities kept up
// to date) against the textbook sweep on a dense W = H A^-1 H^T.
// GCC 12 + AVX-512 reports a false -Wmaybe-uninitialized inside Eigen's dense GEMM kernels.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <random>

#include "anatomy_fixture.hpp"
#include "random_systems.hpp"
#include "engine/contact/solve_contacts.hpp"
#include "engine/scene/wall_distance_by_grid.hpp"

using namespace gw;

TEST_CASE("the grid's range query holds every triangle FCL finds within the radius", "[contact][grid]") {
  const test::Anatomy a = test::load_anatomy("test/coronary/coronary");
  const VesselScene& s = a.scene;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> face(0, static_cast<int>(s.mesh.F.rows()) - 1);
  std::uniform_real_distribution<double> u(-1, 1), radius(0.05, 2.0);
  std::vector<int> fcl_found, near;
  std::size_t total = 0;
  for (int q = 0; q < 300; ++q) {
    // Points around the wall, where the wire's contact points are.
    const Eigen::Vector3d p = s.face_centres.row(face(rng)).transpose() + Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double r = radius(rng);
    triangles_within(s, p, r, fcl_found);
    triangles_near(s, p, r, near);
    std::sort(fcl_found.begin(), fcl_found.end());
    std::sort(near.begin(), near.end());
    REQUIRE(std::adjacent_find(near.begin(), near.end()) == near.end());  // each triangle once
    for (int f : fcl_found) REQUIRE(std::binary_search(near.begin(), near.end(), f));
    for (int f : near) REQUIRE((p - s.face_spheres[f].head<3>()).norm() - s.face_spheres[f][3] <= r);
    total += fcl_found.size();
  }
  CHECK(total > 1000);  // the queries did reach the wall
}

TEST_CASE("the grid's closest wall point is FCL's, bit for bit, near and far from the wall", "[contact][grid]") {
  const test::Anatomy a = test::load_anatomy("test/coronary/coronary");
  const VesselScene& s = a.scene;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> face(0, static_cast<int>(s.mesh.F.rows()) - 1);
  std::uniform_real_distribution<double> u(-1, 1), scale(0.01, 6.0), start(0.01, 3.0);
  for (int q = 0; q < 400; ++q) {
    // Around the wall, inside and outside, up to 6 mm away (the lumen's middle and beyond the mesh).
    const Eigen::Vector3d p =
        s.face_centres.row(face(rng)).transpose() + scale(rng) * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const WallDistance slow = wall_distance(s, p), fast = wall_distance_by_grid(s, p, start(rng));
    REQUIRE(fast.triangle == slow.triangle);
    REQUIRE(fast.signed_distance == slow.signed_distance);
    REQUIRE(fast.closest == slow.closest);
    REQUIRE(fast.inward == slow.inward);
  }
  // Far outside the mesh's box: the search radius grows until it holds the nearest triangle.
  const Eigen::Vector3d far(500, -400, 300);
  const WallDistance slow = wall_distance(s, far), fast = wall_distance_by_grid(s, far, 0.5);
  CHECK(fast.triangle == slow.triangle);
  CHECK(fast.signed_distance == slow.signed_distance);
}

TEST_CASE("the plane early out of the closest-triangle scan changes no answer", "[contact][grid]") {
  // It skips only triangles that could not have replaced the best so far (farther by more than the tie
  // tolerance), so the scan's answer is the one without it, bit for bit, ties on shared edges and
  // vertices included (points on the wall: every distance there is a tie within 1e-12 mm^2).
  const test::Anatomy a = test::load_anatomy("test/coronary/coronary");
  const VesselScene& s = a.scene;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> face(0, static_cast<int>(s.mesh.F.rows()) - 1), corner(0, 2);
  std::uniform_real_distribution<double> u(-1, 1), scale(0.0, 1.0);
  std::vector<int> list;
  int found = 0;
  for (int q = 0; q < 3000; ++q) {
    // Around the wall, and on its vertices and edges (ties between the faces that share them).
    const int f = face(rng);
    Eigen::Vector3d p = s.face_centres.row(f).transpose();
    if (q % 3 == 1) p = s.face_corners[f].col(corner(rng));
    if (q % 3 == 2) p = 0.5 * (s.face_corners[f].col(0) + s.face_corners[f].col(1));
    p += std::pow(10.0, -7 * scale(rng)) * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double cutoff = 0.7;
    triangles_near(s, p, cutoff, list);
    // The scan without the plane early out: the same bounds with every plane zero (no bound, as for
    // a thin face), so that both answers come from the same compiled arithmetic.
    std::vector<Eigen::Vector4d> bounds, spheres_only;
    for (int t : list) {
      bounds.push_back(s.face_spheres[t]);
      bounds.push_back(s.face_planes[t]);
      spheres_only.push_back(s.face_spheres[t]);
      spheres_only.push_back(Eigen::Vector4d::Zero());
    }
    const int hint = q % 2 == 0 || list.empty() ? -1 : static_cast<int>(rng() % list.size());
    int best = hint;
    const WallDistance ref = wall_distance_among(s, p, list, cutoff, nullptr, 0, &best, &spheres_only);
    for (const bool in_order : {false, true}) {
      int position = hint;
      const WallDistance wd =
          wall_distance_among(s, p, list, cutoff, nullptr, 0, &position, in_order ? &bounds : nullptr);
      REQUIRE(wd.triangle == ref.triangle);
      REQUIRE(position == best);
      REQUIRE(wd.signed_distance == ref.signed_distance);
      REQUIRE(wd.closest == ref.closest);
      REQUIRE(wd.inward == ref.inward);
      found += wd.triangle >= 0;
    }
  }
  CHECK(found > 3000);
}

TEST_CASE("a point outside the grid's box finds nothing, an empty mesh is refused", "[contact][grid]") {
  const test::Anatomy a = test::load_anatomy("train/t1_straight_y/t1_straight_y");
  std::vector<int> out{1, 2, 3};
  triangles_near(a.scene, Eigen::Vector3d(1e4, 1e4, 1e4), 1.0, out);
  CHECK(out.empty());
  out = {1};
  triangles_near(a.scene, Eigen::Vector3d(-1e15, 1e15, 0), 1.0, out);  // beyond int cell indices
  CHECK(out.empty());
  CHECK_THROWS_AS(make_triangle_grid(TriangleMesh{}), std::invalid_argument);
}

TEST_CASE("a stray far vertex coarsens the grid instead of overflowing its cell keys", "[contact][grid]") {
  TriangleMesh mesh;
  mesh.V.resize(5, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1e12, -1e12, 1e12;  // the last vertex is used by no face
  mesh.F.resize(4, 3);
  mesh.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  const TriangleGrid g = make_triangle_grid(mesh);
  CHECK(g.dims.maxCoeff() <= 1000001);
  std::vector<int> out;
  grid_candidates(g, Eigen::Vector3d(0.2, 0.2, 0.2), 0.1, out);
  std::sort(out.begin(), out.end());
  CHECK(out == std::vector<int>{0, 1, 2, 3});  // one coarse cell holds the whole tetrahedron
}

namespace {

// Contact rows H (3 per contact: n, t1, t2) over the 6 DOF per node of a chain of `nodes` nodes.
Eigen::MatrixXd contact_rows(const std::vector<ContactPoint>& contacts, int nodes) {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(3 * contacts.size(), 6 * nodes);
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const ContactPoint& cp = contacts[c];
    Eigen::Matrix3d basis;
    basis << cp.n.transpose(), cp.t1.transpose(), cp.t2.transpose();
    h.block<3, 3>(3 * c, 6 * cp.node_a) += cp.wa * basis;
    if (cp.node_b >= 0) h.block<3, 3>(3 * c, 6 * cp.node_b) += cp.wb * basis;
  }
  return h;
}

}  // namespace

TEST_CASE("PGS with lazily built W matches the dense textbook sweep and satisfies Signorini-Coulomb",
          "[contact][pgs]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1), gap(0.0, 0.02);
  const int nodes = 24;
  const double dt = 5e-4, mu = 0.3;
  const BlockTridiagonal a = test::random_spd(nodes, rng);  // a well-coupled chain like the wire's system
  BlockTridiagonalFactor f;
  REQUIRE(factor_block_tridiagonal(a, f));
  // Node and midpoint contacts; about half approach the wall (they will press), half move away.
  std::vector<ContactPoint> contacts;
  for (int i = 2; i < nodes - 1; i += 2) {
    for (int mid = 0; mid < 2; ++mid) {
      ContactPoint c;
      c.point = mid ? nodes + i : i;
      c.node_a = i;
      if (mid) {
        c.node_b = i + 1;
        c.wa = c.wb = 0.5;
      }
      c.n = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
      c.t1 = c.n.unitOrthogonal();
      c.t2 = c.n.cross(c.t1);
      c.gap = gap(rng);
      c.v_free = -60.0 * c.n * (u(rng) + 0.2) + 10.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      contacts.push_back(c);
    }
  }
  const int m = static_cast<int>(contacts.size());
  ContactWorkspace ws;
  prepare_contact_compliance(a, f, 0, contacts, ws);
  const ContactSolveResult res = solve_contact_impulses(contacts, dt, mu, 20000, false, ws);
  REQUIRE(res.residual < 1e-6);
  const Eigen::VectorXd p = ws.impulse.head(3 * m);

  // Dense reference: W from the dense inverse, the same sweep order and local projection.
  const Eigen::MatrixXd dense = test::to_dense(a);
  const Eigen::MatrixXd h = contact_rows(contacts, nodes);
  const Eigen::MatrixXd w = h * dense.ldlt().solve(h.transpose());
  Eigen::VectorXd bias(3 * m);
  for (int c = 0; c < m; ++c) bias.segment<3>(3 * c) << contacts[c].gap / dt + contacts[c].n.dot(contacts[c].v_free),
      contacts[c].t1.dot(contacts[c].v_free), contacts[c].t2.dot(contacts[c].v_free);
  Eigen::VectorXd ref = Eigen::VectorXd::Zero(3 * m);
  for (int it = 0; it < 20000; ++it) {
    for (int c = 0; c < m; ++c) {
      const int r = 3 * c;
      const Eigen::Vector3d uc = w.middleRows(r, 3) * ref + bias.segment<3>(r);
      const double pn = std::max(0.0, ref[r] - uc[0] / w(r, r));
      Eigen::Vector2d pt(ref[r + 1] - uc[1] / w(r + 1, r + 1), ref[r + 2] - uc[2] / w(r + 2, r + 2));
      if (pt.norm() > mu * pn) pt *= pt.norm() > 0 ? mu * pn / pt.norm() : 0.0;
      ref.segment<3>(r) << pn, pt;
    }
  }
  const double scale = ref.cwiseAbs().maxCoeff();
  REQUIRE(scale > 0);
  CHECK((p - ref).cwiseAbs().maxCoeff() < 1e-5 * scale);

  // Signorini (normal) and Coulomb (cone, sticking inside it) at the solution.
  const Eigen::VectorXd vel = w * p + bias;
  const double vscale = bias.cwiseAbs().maxCoeff();
  int pressing = 0, separating = 0;
  for (int c = 0; c < m; ++c) {
    const int r = 3 * c;
    CHECK(p[r] >= 0);
    CHECK(vel[r] >= -1e-4 * vscale);                           // no approach through the wall
    CHECK(std::abs(p[r] * vel[r]) <= 1e-4 * scale * vscale);   // push only where in contact
    const double pt = p.segment<2>(r + 1).norm();
    CHECK(pt <= mu * p[r] * (1 + 1e-9) + 1e-12);
    if (pt < 0.99 * mu * p[r]) CHECK(vel.segment<2>(r + 1).norm() <= 1e-4 * vscale);
    (p[r] > 0 ? pressing : separating) += 1;
  }
  CHECK(pressing > 2);    // the case exercises both kinds of contact
  CHECK(separating > 2);
}
