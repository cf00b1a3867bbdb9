#pragma once
// Synthetic scenes for the report tests: a box "vessel" with a straight centerline, and
// a small tube tree with two bifurcations for the example figure. Millimetres.
#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "lib/report/trajectory.hpp"
#include "base/graph/centerline_graph.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw::test {

// Closed box x, z in [-2, 2], y in [0, 40]: a straight 4 mm "vessel" along +y.
inline TriangleMesh box_vessel() {
  TriangleMesh m;
  m.V.resize(8, 3);
  int k = 0;
  for (double y : {0.0, 40.0})
    for (double z : {-2.0, 2.0})
      for (double x : {-2.0, 2.0}) m.V.row(k++) << x, y, z;
  // vertex index = 4*(y==40) + 2*(z==2) + (x==2)
  m.F.resize(12, 3);
  m.F << 0, 1, 3, 0, 3, 2,  // y = 0
      4, 6, 7, 4, 7, 5,     // y = 40
      0, 4, 5, 0, 5, 1,     // z = -2
      2, 3, 7, 2, 7, 6,     // z = +2
      0, 2, 6, 0, 6, 4,     // x = -2
      1, 5, 7, 1, 7, 3;     // x = +2
  return m;
}

// One branch from the inlet (0,0,0) to target 1 at (0,40,0), points every millimetre.
inline CenterlineGraph straight_graph() {
  CenterlineGraph g;
  CenterlineBranch b;
  b.id = 0;
  for (int i = 0; i <= 40; ++i) {
    b.points.emplace_back(0.0, i, 0.0);
    b.radii.push_back(2.0);
  }
  g.branches.push_back(b);
  g.inlet = {0, Eigen::Vector3d::Zero(), 0, 2.0};
  g.inlet_direction = Eigen::Vector3d::UnitY();
  number_targets(g);
  return g;
}

// A trace along x = -1 (inside the box, off the centerline): push-only for y < 20,
// agent in control above; final wire along x = +1.5.
inline EpisodeTrace box_trace() {
  EpisodeTrace t;
  t.anatomy = "box";
  t.controller = "sac-policy";
  t.target_id = 1;
  t.seed = 42;
  t.outcome = "success";
  t.detail = "reached target 1";
  for (int i = 0; i <= 38; ++i) {
    t.time_s.push_back(0.1 * i);
    t.tip.emplace_back(-1.0, i, 0.0);
    t.action.push_back(std::sin(0.3 * i));
    t.agent_in_control.push_back(i >= 20);
  }
  std::vector<Eigen::Vector3d> wire;
  for (int i = 0; i <= 35; ++i) wire.emplace_back(1.5, i, 0.0);
  t.wire_shapes = {wire};
  t.wire_shape_frame = {38};
  return t;
}

// A tube of `radius` around a polyline: rings of `sides` vertices, open ends.
inline void append_tube(TriangleMesh& m, const std::vector<Eigen::Vector3d>& pts, double radius, int sides = 16) {
  const Eigen::Index base = m.V.rows();
  const auto n = static_cast<Eigen::Index>(pts.size());
  m.V.conservativeResize(base + n * sides, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::size_t a = static_cast<std::size_t>(std::max<Eigen::Index>(i - 1, 0));
    const std::size_t b = static_cast<std::size_t>(std::min<Eigen::Index>(i + 1, n - 1));
    const Eigen::Vector3d t = (pts[b] - pts[a]).normalized();
    const Eigen::Vector3d u = t.unitOrthogonal(), v = t.cross(u);
    for (int s = 0; s < sides; ++s) {
      const double phi = 2.0 * M_PI * s / sides;
      m.V.row(base + i * sides + s) = (pts[static_cast<std::size_t>(i)] + radius * (std::cos(phi) * u + std::sin(phi) * v)).transpose();
    }
  }
  const Eigen::Index f0 = m.F.rows();
  m.F.conservativeResize(f0 + (n - 1) * sides * 2, 3);
  Eigen::Index f = f0;
  for (Eigen::Index i = 0; i + 1 < n; ++i)
    for (int s = 0; s < sides; ++s) {
      const int a = static_cast<int>(base + i * sides + s), b = static_cast<int>(base + i * sides + (s + 1) % sides);
      const int c = a + sides, d = b + sides;
      m.F.row(f++) << a, b, d;
      m.F.row(f++) << a, d, c;
    }
}

// Quadratic Bezier p0 -> p2 pulled towards p1, about one point per millimetre.
inline std::vector<Eigen::Vector3d> bezier(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
  const int n = std::max(2, static_cast<int>(((p1 - p0).norm() + (p2 - p1).norm())));
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i <= n; ++i) {
    const double s = static_cast<double>(i) / n;
    out.push_back((1 - s) * (1 - s) * p0 + 2 * s * (1 - s) * p1 + s * s * p2);
  }
  return out;
}

struct TreeScene {
  TriangleMesh mesh;
  CenterlineGraph graph;
};

// Inlet at the origin, root along +y, bifurcation B0 at y = 60 into a left branch and a
// right branch that bifurcates again (B1), out of plane in z: three targets.
inline TreeScene small_tree() {
  TreeScene s;
  const Eigen::Vector3d b0(0, 60, 0), b1(22, 98, -8);
  struct Spec { int parent; std::vector<Eigen::Vector3d> pts; double r; };
  const std::vector<Spec> specs = {
      {-1, bezier({0, 0, 0}, {0, 30, 0}, b0), 2.0},
      {0, bezier(b0, {-8, 75, 4}, {-26, 96, 8}), 1.6},
      {0, bezier(b0, {6, 78, -2}, b1), 1.7},
      {2, bezier(b1, {24, 115, -10}, {14, 132, -20}), 1.3},
      {2, bezier(b1, {34, 108, -6}, {44, 124, 2}), 1.3},
  };
  for (std::size_t i = 0; i < specs.size(); ++i) {
    CenterlineBranch b;
    b.id = static_cast<int>(i);
    b.parent = specs[i].parent;
    b.points = specs[i].pts;
    b.radii.assign(b.points.size(), specs[i].r);
    s.graph.branches.push_back(b);
    append_tube(s.mesh, b.points, specs[i].r);
  }
  s.graph.bifurcations = {{0, b0, 0, {1, 2}}, {1, b1, 2, {3, 4}}};
  s.graph.inlet = {0, Eigen::Vector3d::Zero(), 0, 2.0};
  s.graph.inlet_direction = Eigen::Vector3d::UnitY();
  number_targets(s.graph);
  return s;
}

// A plausible episode along `route` (inlet first): the tip wobbles around it, the agent
// is in control within 20 mm of a bifurcation, the final wire follows the route.
inline EpisodeTrace episode_along(const std::vector<Eigen::Vector3d>& route, const CenterlineGraph& g,
                                  const std::string& outcome, const std::string& detail, int target_id) {
  EpisodeTrace t;
  t.anatomy = "small-tree";
  t.controller = "sac-policy";
  t.target_id = target_id;
  t.seed = 7;
  t.outcome = outcome;
  t.detail = detail;
  for (std::size_t i = 0; i < route.size(); ++i) {
    const double w = 0.6 * std::sin(0.5 * static_cast<double>(i));
    const Eigen::Vector3d p = route[i] + Eigen::Vector3d(w, 0.0, 0.5 * w);
    bool near = false;
    for (const auto& b : g.bifurcations) near = near || (route[i] - b.position).norm() < 20.0;
    t.time_s.push_back(0.05 * static_cast<double>(i));
    t.tip.push_back(p);
    t.action.push_back(near ? std::sin(0.2 * static_cast<double>(i)) : 0.0);
    t.agent_in_control.push_back(near);
    if (i % 25 == 0 || i + 1 == route.size()) {
      t.wire_shapes.emplace_back(route.begin(), route.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      t.wire_shape_frame.push_back(static_cast<int>(i));
    }
  }
  return t;
}

// A fresh empty directory under the build tree for files a test writes.
inline std::string scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(GW_BINARY_DIR) / "test_report_scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace gw::test
