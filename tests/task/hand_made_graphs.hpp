#pragma once
// Small centerline graphs built by hand, for geometry tests that need no mesh.
#include <cmath>

#include "base/graph/centerline_graph.hpp"

namespace gwtest {

inline std::vector<Eigen::Vector3d> segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double spacing = 1.0) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i <= n; ++i) pts.push_back(a + (b - a) * (static_cast<double>(i) / n));
  return pts;
}

inline gw::CenterlineBranch branch(int id, int parent, const std::vector<Eigen::Vector3d>& pts, double r = 2.0) {
  gw::CenterlineBranch b;
  b.id = id;
  b.parent = parent;
  b.points = pts;
  b.radii.assign(pts.size(), r);
  return b;
}

// Root along +y from the origin (40 mm), two 45-degree children of 30*sqrt(2) mm in the xy plane.
inline gw::CenterlineGraph y_graph() {
  gw::CenterlineGraph g;
  const Eigen::Vector3d o(0, 0, 0), c(0, 40, 0);
  g.inlet.position = o;
  g.inlet.branch = 0;
  g.inlet.radius = 2.0;
  g.inlet_direction = Eigen::Vector3d::UnitY();
  g.branches.push_back(branch(0, -1, segment(o, c)));
  g.branches.push_back(branch(1, 0, segment(c, c + Eigen::Vector3d(-30, 30, 0))));
  g.branches.push_back(branch(2, 0, segment(c, c + Eigen::Vector3d(30, 30, 0))));
  gw::Bifurcation b;
  b.id = 0;
  b.position = c;
  b.parent = 0;
  b.children = {1, 2};
  g.bifurcations.push_back(b);
  for (int leaf : {1, 2}) {
    gw::Terminal t;
    t.position = g.branches[leaf].points.back();
    t.branch = leaf;
    t.radius = 2.0;
    g.targets.push_back(t);
  }
  gw::number_targets(g);
  return g;
}

// Root along +y (40 mm); child 1 continues straight on along +y, child 2 leaves at 90 degrees along +x.
inline gw::CenterlineGraph t_graph() {
  gw::CenterlineGraph g = y_graph();
  const Eigen::Vector3d c(0, 40, 0);
  g.branches[1] = branch(1, 0, segment(c, c + Eigen::Vector3d(0, 40, 0)));
  g.branches[2] = branch(2, 0, segment(c, c + Eigen::Vector3d(40, 0, 0)));
  for (gw::Terminal& t : g.targets) t.position = g.branches[t.branch].points.back();
  gw::number_targets(g);
  return g;
}

// Y graph whose right child splits again 30 mm further (out of plane): 3 targets.
inline gw::CenterlineGraph two_level_tree() {
  gw::CenterlineGraph g = y_graph();
  g.targets.clear();
  const Eigen::Vector3d c2 = g.branches[2].points.back();
  g.branches.push_back(branch(3, 2, segment(c2, c2 + Eigen::Vector3d(0, 30, 20))));
  g.branches.push_back(branch(4, 2, segment(c2, c2 + Eigen::Vector3d(25, 20, -10))));
  gw::Bifurcation b;
  b.id = 1;
  b.position = c2;
  b.parent = 2;
  b.children = {3, 4};
  g.bifurcations.push_back(b);
  for (int leaf : {1, 3, 4}) {
    gw::Terminal t;
    t.position = g.branches[leaf].points.back();
    t.branch = leaf;
    t.radius = 2.0;
    g.targets.push_back(t);
  }
  gw::number_targets(g);
  return g;
}

// Root along +y (40 mm); child 1 continues along +y; child 2 hooks back: out along +x, then down
// to pass 12 mm beside the inlet (the S-shaped training pattern in the extreme).
inline gw::CenterlineGraph hook_graph() {
  gw::CenterlineGraph g;
  const Eigen::Vector3d o(0, 0, 0), c(0, 40, 0);
  g.inlet.position = o;
  g.inlet.branch = 0;
  g.inlet.radius = 2.0;
  g.inlet_direction = Eigen::Vector3d::UnitY();
  g.branches.push_back(branch(0, -1, segment(o, c)));
  g.branches.push_back(branch(1, 0, segment(c, c + Eigen::Vector3d(0, 45, 0))));
  std::vector<Eigen::Vector3d> hook = segment(c, Eigen::Vector3d(12, 44, 0));
  const std::vector<Eigen::Vector3d> down = segment(Eigen::Vector3d(12, 44, 0), Eigen::Vector3d(12, 2, 0));
  hook.insert(hook.end(), down.begin() + 1, down.end());
  g.branches.push_back(branch(2, 0, hook));
  gw::Bifurcation b;
  b.id = 0;
  b.position = c;
  b.parent = 0;
  b.children = {1, 2};
  g.bifurcations.push_back(b);
  gw::number_targets(g);
  return g;
}

}  // namespace gwtest
