#pragma once
// Polylines joined into a tree, then turned into the project's CenterlineGraph: how the readers
// of other tools' centerlines (VMTK .vtp, 3D Slicer .mrk.json) build their graph.
// In:  a root polyline running distally from the inlet, then polylines that each leave the tree
//      at a point found with nearest() (the tree is split there; a new vertex is inserted when
//      the point lies between two vertices).
// Out: graph(): branches in breadth-first order from the root (ids 0..N-1, distal order, a
//      child's first point is its parent's last), a bifurcation wherever polylines leave,
//      the inlet at the root's first point (direction over about two radii), targets at the
//      leaf ends numbered by number_targets.
#include <Eigen/Core>
#include <vector>

#include "base/graph/centerline_graph.hpp"

namespace gw {

struct TreePoint {
  int segment = -1;      // internal polyline index
  size_t index = 0;      // the point lies on the piece [index, index + 1] of that polyline
  double t = 0.0;        // fraction along that piece
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double radius = 0.0;   // interpolated
  double distance = 0.0; // from the query point
};

class PolylineTree {
 public:
  // Throws std::invalid_argument when points and radii differ in count or fewer than 2 points.
  PolylineTree(std::vector<Eigen::Vector3d> points, std::vector<double> radii);

  // The point of the tree nearest to p.
  TreePoint nearest(const Eigen::Vector3d& p) const;

  // A new branch leaving the tree at `at` and running through `points` (which start after the
  // junction). Leaving at the root's first point (the inlet) throws std::invalid_argument;
  // leaving at the free end of a leaf extends that leaf instead of making a bifurcation.
  void attach(const TreePoint& at, const std::vector<Eigen::Vector3d>& points, const std::vector<double>& radii);

  CenterlineGraph graph() const;

 private:
  struct Segment {
    std::vector<Eigen::Vector3d> points;
    std::vector<double> radii;
    int parent = -1;
    std::vector<int> children;
  };
  std::vector<Segment> segments_;
};

}  // namespace gw
