// The task on a moving wall (issue 36 item 2): the centerline graph follows the wall's displacement
// (graph_motion.hpp), the course, lambda, the control spheres and "target reached" are read in the current
// shape, and a wall that does not move leaves the episode as it is.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <memory>

#include "engine/scene/moving_wall.hpp"
#include "engine/scene/swept_tube_mesh.hpp"
#include "task/episode.hpp"
#include "task/graph_motion.hpp"
#include "tests/task/hand_made_graphs.hpp"

namespace {

// A straight tube of radius 2 mm along +y from y = -10 to 45 mm (capped), one ring per mm.
gw::VesselScene straight_tube() {
  Eigen::MatrixX3d c(56, 3);
  for (int i = 0; i < 56; ++i) c.row(i) << 0.0, -10.0 + i, 0.0;
  return gw::make_vessel_scene(gw::swept_tube_mesh(c, 2.0, 24));
}

// Its centerline: one branch from the inlet (origin) to the target at y = 40 mm.
gw::CenterlineGraph straight_graph() {
  gw::CenterlineGraph g;
  g.inlet.position = Eigen::Vector3d::Zero();
  g.inlet.branch = 0;
  g.inlet.radius = 2.0;
  g.inlet_direction = Eigen::Vector3d::UnitY();
  g.branches.push_back(gwtest::branch(0, -1, gwtest::segment(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 40, 0))));
  gw::Terminal t;
  t.position = g.branches[0].points.back();
  t.branch = 0;
  t.radius = 2.0;
  g.targets.push_back(t);
  gw::number_targets(g);
  return g;
}

gw::NavigationTask tube_task(const gw::VesselScene& scene, gw::TaskConfig config = {}) {
  std::vector<gw::Anatomy> anatomies;
  anatomies.push_back(gw::make_anatomy("tube", straight_graph(), std::make_shared<const gw::VesselScene>(scene)));
  return gw::make_navigation_task(config, gw::default_wire_params(), std::move(anatomies));
}

gw::CardiacMotion beat(double bpm) {
  gw::CardiacMotion p;
  p.heart_rate_bpm = bpm;
  p.axis_origin = Eigen::Vector3d(3, 20, -4);
  p.axis_direction = Eigen::Vector3d(0.3, 1.0, 0.2);
  p.contraction_mm = 0.2;  // 20% of the 1 mm reference radius
  p.reference_radius_mm = 1.0;
  p.shortening_mm = 0.1;
  p.reference_length_mm = 1.0;
  p.twist_deg_per_cm = 5.0;
  p.translation_mm = Eigen::Vector3d(1.0, -2.0, 0.5);
  return p;
}

bool same_bits(const gw::Observation& a, const gw::Observation& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

}  // namespace

TEST_CASE("moving wall: a centerline point maps with the wall (cardiac field and phase surfaces)", "[task][moving]") {
  const gw::VesselScene rest = straight_tube();
  gw::CenterlineGraph g = straight_graph();
  const int v = 300;  // a wall vertex; put a centerline point on it
  g.branches[0].points[7] = rest.mesh.V.row(v).transpose();

  SECTION("cardiac field: every point is X + D(X, t), a point on a vertex is that vertex") {
    const gw::VesselScene scene = gw::attach_wall_motion(rest, gw::cardiac_wall_motion(rest.mesh, beat(72)));
    const gw::GraphMotion gm = gw::make_graph_motion(g, scene);
    CHECK(gm.points == static_cast<int>(gw::graph_points(g).size()));
    CHECK(gm.vertex.empty());  // the field is defined everywhere: no weights
    gw::CenterlineGraph now;
    for (double t : {0.07, 0.31, 0.55, 0.9}) {
      gw::graph_at(g, scene, gm, t, now);
      CHECK((now.branches[0].points[7] - gw::current_wall_vertex(scene, v, t)).norm() < 1e-9);
      double moved = 0;
      for (size_t k = 0; k < g.branches[0].points.size(); ++k) {
        Eigen::Vector3d x;
        REQUIRE(gw::wall_field_position(*scene.motion, g.branches[0].points[k], t, x));
        CHECK((now.branches[0].points[k] - x).norm() < 1e-9);
        moved = std::max(moved, (now.branches[0].points[k] - g.branches[0].points[k]).norm());
      }
      CHECK(moved > 0.5);  // the map is not the identity at these times
      CHECK((now.targets[0].position - now.branches[0].points.back()).norm() < 1e-9);
      CHECK((now.inlet.position - now.branches[0].points.front()).norm() < 1e-9);
    }
  }

  SECTION("phase surfaces: a point on a vertex follows it exactly, others a weighted mean of their vertices") {
    std::vector<Eigen::MatrixX3d> frames;
    for (int j = 0; j < 4; ++j) {
      Eigen::MatrixX3d f = rest.mesh.V;
      for (Eigen::Index i = 0; i < f.rows(); ++i)
        f.row(i) += Eigen::RowVector3d(0.5 * std::sin(j + 0.1 * i), 0.3 * j, 0.4 * std::cos(0.05 * i - j));
      frames.push_back(f);
    }
    const gw::VesselScene scene = gw::attach_wall_motion(rest, gw::phase_wall_motion(rest.mesh, frames, 75, 0.2));
    const gw::GraphMotion gm = gw::make_graph_motion(g, scene);
    CHECK(gm.begin.size() == static_cast<size_t>(gm.points) + 1);
    gw::CenterlineGraph now;
    for (double t : {0.0, 0.13, 0.42, 0.77}) {
      gw::graph_at(g, scene, gm, t, now);
      CHECK((now.branches[0].points[7] - gw::current_wall_vertex(scene, v, t)).norm() < 1e-9);
      // Point k of the branch (1 + k in graph order): its displacement lies within its vertices' range.
      for (size_t k = 0; k < g.branches[0].points.size(); ++k) {
        const int i = 1 + static_cast<int>(k);
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
        for (int j = gm.begin[static_cast<size_t>(i)]; j < gm.begin[static_cast<size_t>(i) + 1]; ++j) {
          const int u = gm.vertex[static_cast<size_t>(j)];
          const Eigen::Vector3d d = gw::current_wall_vertex(scene, u, t) - rest.mesh.V.row(u).transpose();
          lo = lo.cwiseMin(d);
          hi = hi.cwiseMax(d);
        }
        const Eigen::Vector3d d = now.branches[0].points[k] - g.branches[0].points[k];
        CHECK((d.array() >= lo.array() - 1e-12).all());
        CHECK((d.array() <= hi.array() + 1e-12).all());
      }
    }
  }
}

TEST_CASE("moving wall: 0 bpm is today's episode bit for bit, a beat of zero amplitude the same to 1e-9",
          "[task][moving]") {
  const gw::VesselScene rest = straight_tube();
  const gw::NavigationTask still = tube_task(rest);
  SECTION("0 bpm: no motion reaches the task") {
    const gw::VesselScene frozen = gw::attach_wall_motion(rest, gw::cardiac_wall_motion(rest.mesh, beat(0)));
    const gw::NavigationTask task = tube_task(frozen);
    CHECK(task.graph_motions[0].points == 0);
    gw::EpisodeState a = gw::reset_episode(still, 0, 1, 5), b = gw::reset_episode(task, 0, 1, 5);
    for (int k = 0; k < 40 && !a.done; ++k) {
      const double action = std::sin(0.3 * k);
      const gw::StepOutcome oa = gw::step_episode(still, a, action), ob = gw::step_episode(task, b, action);
      REQUIRE(same_bits(oa.obs, ob.obs));
      REQUIRE(oa.reward == ob.reward);
      REQUIRE(a.tip == b.tip);
      CHECK_FALSE(b.shape.valid);
    }
  }
  SECTION("a beat of zero amplitude runs the moving code path and reads the same course") {
    gw::CardiacMotion none;
    none.heart_rate_bpm = 60;
    const gw::VesselScene beating = gw::attach_wall_motion(rest, gw::cardiac_wall_motion(rest.mesh, none));
    REQUIRE(beating.motion);
    const gw::NavigationTask task = tube_task(beating);
    REQUIRE(task.graph_motions[0].points > 0);
    gw::EpisodeState a = gw::reset_episode(still, 0, 1, 5), b = gw::reset_episode(task, 0, 1, 5);
    for (int k = 0; k < 40 && !a.done; ++k) {
      const double action = std::sin(0.3 * k);
      const gw::StepOutcome oa = gw::step_episode(still, a, action), ob = gw::step_episode(task, b, action);
      REQUIRE(b.shape.valid);
      CHECK(b.shape.course.line.points == a.course->line.points);  // X + 0 = X exactly
      for (int i = 0; i < gw::kObservationSize; ++i) REQUIRE(oa.obs[i] == Approx(ob.obs[i]).margin(1e-9));
      REQUIRE((a.tip - b.tip).norm() < 1e-9);
      REQUIRE(oa.terminated == ob.terminated);
    }
  }
}

TEST_CASE("moving wall: progress, lambda and 'target reached' are measured in the moving frame", "[task][moving]") {
  // The tube shaken sideways and along its axis (1.2 and 1.5 mm at 60 bpm); the wire only pushed.
  const gw::VesselScene rest = straight_tube();
  const gw::VesselScene shaken = gw::attach_wall_motion(
      rest, gw::rigid_wall_motion(rest.mesh, Eigen::Vector3d::Zero(), Eigen::Vector3d(1.2, 1.5, 0.0), 60.0));
  const gw::NavigationTask task = tube_task(shaken);
  const Eigen::Vector3d target = task.anatomies[0].graph.targets[0].position;
  gw::EpisodeState s = gw::reset_episode(task, 0, 1, 3);
  double largest_shift = 0, largest_rest_error = 0;
  bool success = false;
  while (!s.done) {
    const gw::StepOutcome out = gw::step_episode(task, s, 0.0);
    const double t = s.wire.time;
    Eigen::Vector3d moved;
    REQUIRE(gw::wall_field_position(*shaken.motion, target, t, moved));
    const Eigen::Vector3d shift = moved - target;  // the tube's displacement at t
    largest_shift = std::max(largest_shift, shift.norm());
    // The target checked is where the vessel holds it now.
    CHECK((gw::current_course(s).target - moved).norm() < 1e-9);
    CHECK(out.info.tip_to_target_mm == Approx((s.tip - moved).norm()).margin(1e-9));
    largest_rest_error = std::max(largest_rest_error, std::abs(out.info.tip_to_target_mm - (s.tip - target).norm()));
    // Progress and lambda along the moved centerline (the tube's axis shifted by `shift`).
    const double along = s.tip.y() - shift.y();
    if (along > 0.5 && along < 39.5) {
      CHECK(s.progress_mm == Approx(along).margin(1e-9));
      CHECK(s.lambda_mm == Approx(40.0 - along).margin(1e-9));
      CHECK(s.course_distance_mm == Approx(std::hypot(s.tip.x() - shift.x(), s.tip.z() - shift.z())).margin(1e-9));
    }
    success = out.info.success;
  }
  CHECK(success);
  CHECK(largest_shift > 1.0);
  CHECK(largest_rest_error > 0.3);  // the rest target would have given other distances
}
