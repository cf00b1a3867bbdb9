#include "base/graph/polyline_tree.hpp"

#include <algorithm>
#include <limits>
#include <queue>
#include <stdexcept>

namespace gw {

PolylineTree::PolylineTree(std::vector<Eigen::Vector3d> points, std::vector<double> radii) {
  if (points.size() != radii.size()) throw std::invalid_argument("a polyline has different numbers of points and radii");
  if (points.size() < 2) throw std::invalid_argument("the first polyline has fewer than 2 points");
  segments_.push_back({std::move(points), std::move(radii), -1, {}});
}

TreePoint PolylineTree::nearest(const Eigen::Vector3d& p) const {
  TreePoint best;
  best.distance = std::numeric_limits<double>::infinity();
  for (size_t s = 0; s < segments_.size(); ++s) {
    const Segment& seg = segments_[s];
    for (size_t i = 0; i + 1 < seg.points.size(); ++i) {
      const Eigen::Vector3d a = seg.points[i], ab = seg.points[i + 1] - a;
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const Eigen::Vector3d q = a + t * ab;
      const double d = (p - q).norm();
      if (d < best.distance) {
        best = {static_cast<int>(s), i, t, q, (1 - t) * seg.radii[i] + t * seg.radii[i + 1], d};
      }
    }
  }
  return best;
}

void PolylineTree::attach(const TreePoint& at, const std::vector<Eigen::Vector3d>& points,
                          const std::vector<double>& radii) {
  if (points.size() != radii.size()) throw std::invalid_argument("a polyline has different numbers of points and radii");
  if (points.empty()) return;
  if (at.segment < 0 || at.segment >= static_cast<int>(segments_.size()))
    throw std::invalid_argument("attach: no such tree point");
  int s = at.segment;
  // Snap to a vertex when the junction is within a fifth of a piece of it, else insert one.
  size_t k;
  if (at.t <= 0.2) {
    k = at.index;
  } else if (at.t >= 0.8) {
    k = at.index + 1;
  } else {
    Segment& seg = segments_[static_cast<size_t>(s)];
    k = at.index + 1;
    seg.points.insert(seg.points.begin() + static_cast<long>(k), at.position);
    seg.radii.insert(seg.radii.begin() + static_cast<long>(k), at.radius);
  }
  if (k == 0) {
    const int parent = segments_[static_cast<size_t>(s)].parent;
    if (parent < 0) throw std::invalid_argument("a polyline leaves the tree at the inlet itself");
    s = parent;  // a child's first point is its parent's end: leave from there
    k = segments_[static_cast<size_t>(s)].points.size() - 1;
  }
  Segment& seg = segments_[static_cast<size_t>(s)];
  const Eigen::Vector3d junction = seg.points[k];
  const double junction_radius = seg.radii[k];
  if (k + 1 == seg.points.size() && seg.children.empty()) {  // the free end of a leaf: extend it
    seg.points.insert(seg.points.end(), points.begin(), points.end());
    seg.radii.insert(seg.radii.end(), radii.begin(), radii.end());
    return;
  }
  if (k + 1 < seg.points.size()) {  // split: the distal part becomes a child holding the old children
    Segment tail;
    tail.points.assign(seg.points.begin() + static_cast<long>(k), seg.points.end());
    tail.radii.assign(seg.radii.begin() + static_cast<long>(k), seg.radii.end());
    tail.parent = s;
    tail.children = std::move(seg.children);
    seg.points.resize(k + 1);
    seg.radii.resize(k + 1);
    seg.children.clear();
    const int t = static_cast<int>(segments_.size());
    for (int c : tail.children) segments_[static_cast<size_t>(c)].parent = t;
    segments_.push_back(std::move(tail));  // invalidates seg
    segments_[static_cast<size_t>(s)].children.push_back(t);
  }
  Segment child;
  child.points.push_back(junction);
  child.radii.push_back(junction_radius);
  child.points.insert(child.points.end(), points.begin(), points.end());
  child.radii.insert(child.radii.end(), radii.begin(), radii.end());
  child.parent = s;
  segments_[static_cast<size_t>(s)].children.push_back(static_cast<int>(segments_.size()));
  segments_.push_back(std::move(child));
}

CenterlineGraph PolylineTree::graph() const {
  CenterlineGraph g;
  std::queue<std::pair<int, int>> queue;  // segment, parent branch id
  queue.push({0, -1});
  while (!queue.empty()) {
    const auto [s, parent] = queue.front();
    queue.pop();
    const Segment& seg = segments_[static_cast<size_t>(s)];
    CenterlineBranch b;
    b.id = static_cast<int>(g.branches.size());
    b.parent = parent;
    b.points = seg.points;
    b.radii = seg.radii;
    if (!seg.children.empty()) {
      Bifurcation bif;
      bif.id = static_cast<int>(g.bifurcations.size());
      bif.position = seg.points.back();
      bif.parent = b.id;
      // Children get consecutive breadth-first ids after everything already queued.
      const int first_child = static_cast<int>(g.branches.size() + 1 + queue.size());
      for (size_t c = 0; c < seg.children.size(); ++c) bif.children.push_back(first_child + static_cast<int>(c));
      g.bifurcations.push_back(std::move(bif));
      for (int c : seg.children) queue.push({c, b.id});
    }
    g.branches.push_back(std::move(b));
  }
  const CenterlineBranch& root = g.branches.front();
  g.inlet.id = 0;
  g.inlet.position = root.points.front();
  g.inlet.branch = 0;
  g.inlet.radius = root.radii.front();
  // Direction into the vessel: over about two radii of the root branch (as extraction does).
  const double ahead = 2.0 * root.radii.front();
  Eigen::Vector3d towards = root.points.back();
  double run = 0.0;
  for (size_t i = 1; i < root.points.size(); ++i) {
    run += (root.points[i] - root.points[i - 1]).norm();
    if (run >= ahead && (root.points[i] - root.points.front()).norm() > 0) {
      towards = root.points[i];
      break;
    }
  }
  if ((towards - root.points.front()).norm() > 0) g.inlet_direction = (towards - root.points.front()).normalized();
  number_targets(g);
  return g;
}

}  // namespace gw
