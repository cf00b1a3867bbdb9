// The moving wall (issue 36): the cardiac waveform, the bounds the broad phase relies on, queries on the
// lazily evaluated current shape against a full rebuild of the scene at that time, and the static case
// (0 bpm, zero amplitude) stepping like today's rigid wall.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <limits>
#include <algorithm>
#include <random>

#include "anatomy_fixture.hpp"
#include "engine/contact/detect_contacts.hpp"
#include "engine/scene/closest_point_triangle.hpp"
#include "engine/scene/moving_wall.hpp"
#include "engine/scene/swept_tube_mesh.hpp"
#include "engine/sim/step.hpp"

using namespace gw;

namespace {

// A tube of radius 1.5 mm bent by 90 degrees (radius 15 mm) in the x-y plane, 48 segments per ring.
TriangleMesh bent_tube() {
  Eigen::MatrixX3d c(60, 3);
  for (int i = 0; i < 60; ++i) {
    const double a = 0.5 * M_PI * i / 59.0;
    c.row(i) << 15.0 * std::sin(a), 15.0 * (1.0 - std::cos(a)), 0.0;
  }
  return swept_tube_mesh(c, 1.5, 48);
}

CardiacMotion strong_beat() {
  CardiacMotion p;
  p.heart_rate_bpm = 72;
  p.axis_origin = Eigen::Vector3d(5, 20, -10);
  p.axis_direction = Eigen::Vector3d(0.2, 0.3, 1.0);
  p.contraction_mm = 2.0;
  p.shortening_mm = 1.0;
  p.twist_deg_per_cm = 4.0;
  p.rotation_deg = 3.0;
  p.translation_mm = Eigen::Vector3d(0.5, -0.8, 0.3);
  return p;
}

// Positions of every vertex at time t.
Eigen::MatrixX3d shape_at(const WallMotion& m, const TriangleMesh& rest, double t) {
  Eigen::MatrixX3d x(rest.V.rows(), 3);
  for (Eigen::Index i = 0; i < rest.V.rows(); ++i) x.row(i) = wall_vertex_position(m, rest, static_cast<int>(i), t).transpose();
  return x;
}

}  // namespace

TEST_CASE("cardiac waveform: rest at end-diastole, 1 at end-systole after a third of the cycle", "[moving_wall]") {
  CHECK(cardiac_activation(0.0, 1.0 / 3) == 0.0);
  CHECK(cardiac_activation(1.0 / 3, 1.0 / 3) == Approx(1.0));
  CHECK(cardiac_activation(1.0 / 6, 1.0 / 3) == Approx(0.5));
  CHECK(cardiac_activation(2.0 / 3, 1.0 / 3) == Approx(0.5));
  CHECK(cardiac_activation(0.999999, 1.0 / 3) == Approx(0.0).margin(1e-9));
  // C1: one-sided slopes agree at the joins (both zero).
  const double e = 1e-6;
  for (double join : {1.0 / 3, 1.0})
    CHECK(std::abs(cardiac_activation(join - e, 1.0 / 3) - cardiac_activation(std::fmod(join + e, 1.0), 1.0 / 3)) < 1e-9);
  WallMotion m;
  m.heart_rate_bpm = 60;
  CHECK(cardiac_phase(m, 0.25) == Approx(0.25));
  CHECK(cardiac_phase(m, 3.75) == Approx(0.75));
  m.heart_rate_bpm = 0;
  m.phase_offset = 0.4;
  CHECK(cardiac_phase(m, 123.0) == Approx(0.4));
}

TEST_CASE("wall motion bounds hold for every vertex: displacement and travel between two times", "[moving_wall]") {
  const TriangleMesh rest = bent_tube();
  std::vector<Eigen::MatrixX3d> frames;
  for (int j = 0; j < 5; ++j) {
    Eigen::MatrixX3d f = rest.V;
    for (Eigen::Index i = 0; i < f.rows(); ++i)
      f.row(i) += Eigen::RowVector3d(0.3 * std::sin(j + 0.1 * i), 0.2 * std::cos(2 * j + 0.05 * i), 0.1 * j);
    frames.push_back(f);
  }
  const std::vector<WallMotion> motions = {
      rigid_wall_motion(rest, Eigen::Vector3d(3, -2, 1), Eigen::Vector3d(0.5, 1.0, -0.7), 90),
      cardiac_wall_motion(rest, strong_beat()), phase_wall_motion(rest, frames, 80, 0.3)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> time(0.0, 3.0);
  for (const WallMotion& m : motions) {
    for (int k = 0; k < 40; ++k) {
      const double t0 = time(rng), t1 = k % 4 == 0 ? t0 + 1e-4 : time(rng);
      const Eigen::MatrixX3d x0 = shape_at(m, rest, t0), x1 = shape_at(m, rest, t1);
      const double travel = (x1 - x0).rowwise().norm().maxCoeff();
      const double reach = (x1 - rest.V).rowwise().norm().maxCoeff();
      INFO("kind " << static_cast<int>(m.kind) << " t0 " << t0 << " t1 " << t1);
      CHECK(travel <= wall_max_travel(m, t0, t1));
      CHECK(reach <= wall_max_displacement(m, t1));
      if (m.kind != WallMotionKind::phases)  // (phases: per-segment maxima summed, looser by design)
        CHECK(wall_max_travel(m, t0, t1) <= 2.0 * travel + 1e-6);  // not uselessly loose
    }
  }
}

TEST_CASE("queries on a moving wall equal those on the scene rebuilt at that time", "[moving_wall]") {
  const TriangleMesh rest = bent_tube();
  const VesselScene still = make_vessel_scene(rest);
  const std::vector<WallMotion> motions = {
      cardiac_wall_motion(rest, strong_beat()),
      rigid_wall_motion(rest, Eigen::Vector3d(2, 0, 1), Eigen::Vector3d(0, 1.2, 0.4), 100)};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (const WallMotion& motion : motions) {
    const VesselScene beating = attach_wall_motion(still, motion);
    REQUIRE(beating.motion);
    for (double t : {0.0, 0.13, 0.31, 0.5, 0.77, 1.9}) {
      const VesselScene rebuilt = vessel_scene_at(beating, t);
      for (int k = 0; k < 60; ++k) {
        // Points near the current wall: a vertex at t pushed in or out by up to 0.6 mm.
        const int v = static_cast<int>((u(rng) * 0.5 + 0.5) * (rest.V.rows() - 3));
        const Eigen::Vector3d p = rebuilt.mesh.V.row(v).transpose() + 0.6 * Eigen::Vector3d(u(rng), u(rng), u(rng));
        const WallDistance a = wall_distance_at(beating, t, p), b = wall_distance(rebuilt, p);
        INFO("t " << t << " p " << p.transpose());
        CHECK(a.signed_distance == Approx(b.signed_distance).margin(1e-9));
        CHECK((a.inward - b.inward).norm() < 1e-9);
        CHECK((a.closest - b.closest).norm() < 1e-9);
        // The range query holds every triangle within 0.8 mm (brute force on the rebuilt scene).
        std::vector<int> near;
        triangles_near_at(beating, t, p, 0.8, near);
        std::sort(near.begin(), near.end());
        for (int f = 0; f < rebuilt.mesh.F.rows(); ++f) {
          const Eigen::Matrix3d& c = rebuilt.face_corners[f];
          int region = 0;
          if ((p - closest_point_on_triangle(p, c.col(0), c.col(1), c.col(2), region)).norm() <= 0.8)
            CHECK(std::binary_search(near.begin(), near.end(), f));
        }
        ++compared;
      }
    }
  }
  CHECK(compared == 720);
}

TEST_CASE("the contact cache stays exact while the wall moves: cached distances equal fresh ones", "[moving_wall]") {
  // Push a wire into a beating bent tube; after every step, each contact point's cached distance (lists
  // built earlier, bounds reduced by the wall's travel) equals the one from an empty cache.
  const TriangleMesh rest = bent_tube();
  CardiacMotion beat;  // about an axis through the inlet, so the introducer's mouth stays in the lumen
  beat.heart_rate_bpm = 100;
  beat.contraction_mm = 0.6;
  beat.shortening_mm = 0.3;
  beat.twist_deg_per_cm = 2.0;
  beat.rotation_deg = 1.0;
  const VesselScene scene = attach_wall_motion(make_vessel_scene(rest), cardiac_wall_motion(rest, beat));
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  const Eigen::Vector3d inlet(0.05, 0, 0);
  WireState s = make_initial_state(m, inlet, Eigen::Vector3d::UnitX(), 0.0, 2.0);
  int checked = 0, steps = 0;
  for (; steps < 120; ++steps) {
    const StepReport rep = step(m, &scene, Control{15.0, 0.0}, s);
    if (!rep.ok) break;
    WireState fresh = s;
    fresh.wall_cache.clear();
    for (int pnt = 0; pnt < contact_point_count(m); ++pnt) {
      if (!contact_point_active(m, s, pnt)) continue;
      const Eigen::Vector3d p = contact_point_position(m, s.x, pnt);
      const double need = m.radius_mm + 0.3;
      const WallDistance a = cached_wall_distance(m, scene, s, pnt, p, need);
      const WallDistance b = cached_wall_distance(m, scene, fresh, pnt, p, need);
      if (b.triangle < 0 || b.signed_distance >= need) continue;  // only the exact answers must agree
      CHECK(a.signed_distance == Approx(b.signed_distance).margin(1e-12));
      ++checked;
    }
  }
  INFO("steps " << steps << " checked " << checked);
  CHECK(steps == 120);
  CHECK(checked > 100);
}

TEST_CASE("moving wall: rest-frame candidate lists miss nothing, cached queries against brute force over many sub-steps", "[moving_wall]") {
  // The candidate lists of a rigid or cardiac wall live in the rest configuration (detect_contacts.cpp).
  // Push a wire through a beating / shaken bent tube for 2400 sub-steps; after every control step (20
  // sub-steps) and at the middle of the next sub-step (a wall time the lists never saw), every active
  // point's cached distance must equal the brute-force distance to all current triangles whenever that
  // is below the query's need, and be a lower bound >= need otherwise; the side (inside/outside) must
  // match the scene rebuilt at that time.
  const TriangleMesh rest = bent_tube();
  CardiacMotion beat = strong_beat();  // 2 mm contraction, 4 deg/cm twist, translation
  beat.heart_rate_bpm = 100;
  beat.axis_origin = Eigen::Vector3d(0, 0, 0);  // through the inlet: the introducer's mouth stays in the lumen
  beat.axis_direction = Eigen::Vector3d(0.1, 0.2, 1.0);
  beat.contraction_mm = 0.8;
  beat.translation_mm = Eigen::Vector3d::Zero();
  beat.has_fixed_point = true;
  beat.fixed_point = Eigen::Vector3d(0.05, 0, 0);
  const std::vector<WallMotion> motions = {
      cardiac_wall_motion(rest, beat), rigid_wall_motion(rest, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0.3, 0.2), 100)};
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  const double h = m.dt / m.substeps;
  long exact = 0, bounded = 0, lists_gathered = 0;
  for (const WallMotion& motion : motions) {
    const VesselScene scene = attach_wall_motion(make_vessel_scene(rest), motion);
    REQUIRE(scene.motion);
    WireState s = make_initial_state(m, Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d::UnitX(), 0.0, 2.0);
    int steps = 0;
    for (; steps < 120; ++steps) {
      const StepReport rep = step(m, &scene, Control{15.0, 0.0}, s);
      if (!rep.ok) break;
      for (const double t : {s.time, s.time + 0.5 * h}) {
        const VesselScene now = vessel_scene_at(scene, t);
        for (int pnt = 0; pnt < contact_point_count(m); ++pnt) {
          if (!contact_point_active(m, s, pnt)) continue;
          const Eigen::Vector3d p = contact_point_position(m, s.x, pnt);
          double brute = std::numeric_limits<double>::infinity();  // every current triangle
          for (int f = 0; f < now.mesh.F.rows(); ++f) {
            const Eigen::Vector4d& sphere = now.face_spheres[f];
            if ((p - sphere.head<3>()).norm() - sphere[3] > brute) continue;
            const Eigen::Matrix3d& c = now.face_corners[f];
            int region = 0;
            brute = std::min(brute, (p - closest_point_on_triangle(p, c.col(0), c.col(1), c.col(2), region)).norm());
          }
          const bool inside = wall_distance(now, p).signed_distance > 0;
          for (const double need : {m.radius_mm + m.params.contact_margin_mm, m.radius_mm + 0.4}) {
            const double gathered = s.wall_cache.empty() ? -1 : s.wall_cache[pnt].gathered;
            const WallDistance a = cached_wall_distance(m, scene, s, pnt, p, need, false, t);
            if (s.wall_cache[pnt].gathered != gathered) ++lists_gathered;
            INFO("motion " << static_cast<int>(motion.kind) << " step " << steps << " t " << t << " point " << pnt
                           << " need " << need << " brute " << brute << " cached " << a.signed_distance);
            if (brute < need) {
              REQUIRE(a.triangle >= 0);
              CHECK(std::abs(a.signed_distance) == Approx(brute).margin(1e-9));
              CHECK((a.signed_distance > 0) == inside);
              ++exact;
            } else {
              CHECK(a.signed_distance >= need - 1e-9);  // a lower bound, inside
              CHECK(inside);
              ++bounded;
            }
          }
        }
      }
    }
    CHECK(steps == 120);
  }
  INFO("exact " << exact << " bounded " << bounded << " lists gathered " << lists_gathered);
  CHECK(exact > 2000);
  CHECK(bounded > 2000);
}

TEST_CASE("a static field steps exactly like the rigid wall: 0 bpm and zero amplitude", "[moving_wall][determinism]") {
  const test::Anatomy a = test::load_anatomy("train/t3_out_of_plane_steep/t3_out_of_plane_steep");
  const WireModel m = make_wire_model(default_wire_params(), 0.01);
  CardiacMotion frozen = strong_beat();
  frozen.heart_rate_bpm = 0;  // 0 bpm at end-diastole: the rest shape, attached as the static scene itself
  const VesselScene at_rest = attach_wall_motion(a.scene, cardiac_wall_motion(a.scene.mesh, frozen));
  CHECK(!at_rest.motion);
  CardiacMotion flat;  // a beating heart with zero amplitudes: the moving-wall code path, a wall that stays put
  flat.heart_rate_bpm = 72;
  flat.axis_origin = a.inlet;
  const VesselScene beating_flat = attach_wall_motion(a.scene, cardiac_wall_motion(a.scene.mesh, flat));
  REQUIRE(beating_flat.motion);
  WireState s0 = make_initial_state(m, a.inlet, a.direction, 0.3, 2.0), s1 = s0, s2 = s0;
  double diff_flat = 0;
  for (int i = 0; i < 300; ++i) {
    const Control c{20.0, i < 150 ? 0.5 : -0.4};
    REQUIRE(step(m, &a.scene, c, s0).ok);
    REQUIRE(step(m, &at_rest, c, s1).ok);
    REQUIRE(step(m, &beating_flat, c, s2).ok);
  }
  for (int i = 0; i < m.nodes; ++i) {
    REQUIRE((s0.x[i] - s1.x[i]).norm() == 0.0);  // bit-identical
    diff_flat = std::max(diff_flat, (s0.x[i] - s2.x[i]).norm());
  }
  INFO("zero-amplitude beating wall vs rigid wall: largest node difference " << diff_flat << " mm");
  CHECK(diff_flat < 1e-9);
  // 0 bpm frozen at mid-systole: the static scene of that shape.
  frozen.phase_offset = 0.2;
  const VesselScene held = attach_wall_motion(a.scene, cardiac_wall_motion(a.scene.mesh, frozen));
  CHECK(!held.motion);
  CHECK((held.mesh.V - a.scene.mesh.V).rowwise().norm().maxCoeff() > 0.1);
}

TEST_CASE("wall motion inputs are checked", "[moving_wall]") {
  const TriangleMesh rest = bent_tube();
  CardiacMotion p = strong_beat();
  p.contraction_mm = 1000;
  CHECK_THROWS_WITH(cardiac_wall_motion(rest, p), Catch::Contains("invertible"));
  p = strong_beat();
  p.heart_rate_bpm = -5;
  CHECK_THROWS_WITH(cardiac_wall_motion(rest, p), Catch::Contains("heart rate"));
  p = strong_beat();
  p.axis_direction.setZero();
  CHECK_THROWS_WITH(cardiac_wall_motion(rest, p), Catch::Contains("axis"));
  CHECK_THROWS_WITH(phase_wall_motion(rest, {rest.V}, 60), Catch::Contains("two"));
  CHECK_THROWS_WITH(phase_wall_motion(rest, {rest.V, rest.V.topRows(5)}, 60), Catch::Contains("vertices"));
  const VesselScene scene = make_vessel_scene(rest);
  const TriangleMesh other = swept_tube_mesh(Eigen::MatrixX3d(Eigen::Matrix<double, 2, 3>{{0, 0, 0}, {5, 0, 0}}), 1.0, 8);
  CHECK_THROWS_WITH(attach_wall_motion(scene, rigid_wall_motion(other, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero(), 0)),
                    Catch::Contains("another mesh"));
}

TEST_CASE("the rest-configuration query goes through the field's inverse, not the global bound", "[moving_wall]") {
  // The generator's coronary field (12% contraction, 10% shortening, 2.5 deg/cm twist) on a tube 30 mm
  // from the axis: at end-systole the wall moves by millimetres, yet a 0.8 mm query needs a rest ball
  // barely larger (the map's smallest stretch and curvature), centred on p's pre-image.
  Eigen::MatrixX3d c(40, 3);
  for (int i = 0; i < 40; ++i) c.row(i) << 30.0, -20.0 + i, 40.0 - 2.0 * i;
  const TriangleMesh rest = swept_tube_mesh(c, 1.5, 24);
  CardiacMotion field;
  field.heart_rate_bpm = 60;
  field.axis_direction = Eigen::Vector3d(0, 0, -1);
  field.contraction_mm = 0.12;
  field.reference_radius_mm = 1;
  field.shortening_mm = 0.1;
  field.reference_length_mm = 1;
  field.twist_deg_per_cm = 2.5;
  const WallMotion m = cardiac_wall_motion(rest, field);
  const double t = 1.0 / 3.0;  // end-systole
  REQUIRE(wall_max_displacement(m, t) > 3.0);
  for (int v : {0, 100, 500, 900}) {
    const Eigen::Vector3d p = wall_vertex_position(m, rest, v, t);
    Eigen::Vector3d centre;
    double radius = 0;
    rest_query_ball(m, p, 0.8, t, centre, radius);
    CHECK(radius < 1.2);
    CHECK((centre - rest.V.row(v).transpose()).norm() < 1e-6);
  }
}

TEST_CASE("a cardiac motion file is read, and its mistakes named", "[moving_wall]") {
  const std::string path = std::string(GW_BINARY_DIR) + "/test_motion.json";
  {
    std::ofstream out(path);
    out << R"({"heart_rate_bpm": 72, "axis_origin": [1, 2, 3], "axis_direction": [0, 0, -1], "contraction_mm": 2,
              "twist_deg_per_cm": 2.5, "translation_mm": [0, 1, 0], "fixed_point": [4, 5, 6]})";
  }
  const CardiacMotion m = load_cardiac_motion(path);
  CHECK(m.heart_rate_bpm == 72);
  CHECK(m.axis_origin == Eigen::Vector3d(1, 2, 3));
  CHECK(m.contraction_mm == 2);
  CHECK(m.has_fixed_point);
  CHECK(m.fixed_point == Eigen::Vector3d(4, 5, 6));
  CHECK(m.systole_fraction == Approx(1.0 / 3));
  {
    std::ofstream out(path);
    out << R"({"heart_rate": 72})";
  }
  CHECK_THROWS_WITH(load_cardiac_motion(path), Catch::Contains("unknown key \"heart_rate\""));
  {
    std::ofstream out(path);
    out << R"({"translation_mm": [0, 1]})";
  }
  CHECK_THROWS_WITH(load_cardiac_motion(path), Catch::Contains("three numbers"));
  // A fixed point stays put.
  const TriangleMesh rest = bent_tube();
  CardiacMotion held = strong_beat();
  held.has_fixed_point = true;
  held.fixed_point = rest.V.row(7).transpose();
  const WallMotion w = cardiac_wall_motion(rest, held);
  CHECK((wall_vertex_position(w, rest, 7, 0.3) - rest.V.row(7).transpose()).norm() < 1e-12);
  CHECK((wall_vertex_position(w, rest, 700, 0.3) - rest.V.row(700).transpose()).norm() > 0.1);
}
