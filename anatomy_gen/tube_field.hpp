#pragma once
// The implicit surface of a vessel tree: a signed distance-like field, negative inside.
// Each branch is a tube (distance to its centreline minus the local radius), with flat
// caps at the inlet and outlets; branches are joined by a polynomial smooth minimum of
// width blend x radius, which rounds every junction (no crease, no slit at the carina).
#include <Eigen/Core>
#include <vector>

#include "anatomy_gen/tree_geometry.hpp"

namespace gw {

class TubeField {
 public:
  explicit TubeField(const TreeGeometry& geometry);

  // Field value at p (mm): < 0 inside the vessel, 0 on the wall. Exact distance to the
  // wall near a single tube; only the sign is meaningful far (> a radius) from the wall.
  double value(const Eigen::Vector3d& p) const;

  // Radius of the tube whose wall is nearest p (the largest radius when p is far away).
  double local_radius(const Eigen::Vector3d& p) const;

  // Hard union (no blend), for checks: the analytic tube volume without junction fillets.
  double hard_value(const Eigen::Vector3d& p) const;

 private:
  struct Segment {
    Eigen::Vector3d a, b;
    double ra, rb;
    int branch;
    int group;  // 0 body, 1 inlet-cap zone, 2 outlet-cap zone: caps clip only their own zone
  };
  struct Query {
    double value;
    double radius;
  };
  Query evaluate(const Eigen::Vector3d& p, bool blend) const;
  long cell_of(const Eigen::Vector3i& c) const;

  struct Plane {
    Eigen::Vector3d center, normal;
  };
  std::vector<Plane> start_cap_, end_cap_;  // per branch; used by groups 1 and 2
  double blend_ = 0.5;
  double max_radius_ = 1.0;
  int branches_ = 0;
  std::vector<Segment> segments_;
  // Uniform grid over the tubes: each cell lists the segments that can reach it.
  Eigen::Vector3d origin_;
  double cell_ = 1.0;
  Eigen::Vector3i dims_;
  std::vector<int> cell_start_;  // CSR offsets, size cells + 1
  std::vector<int> cell_items_;
};

}  // namespace gw
