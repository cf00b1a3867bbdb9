#pragma once
// Geometric queries against the vessel wall (a closed triangle surface): distance to the
// wall and the first wall hit along a ray. Backed by a CGAL AABB tree kept out of this
// header (CGAL is slow to compile).
#include <Eigen/Core>
#include <limits>
#include <memory>

#include "base/mesh/triangle_mesh.hpp"

namespace gw {

class VesselWall {
 public:
  // Builds the search tree over the faces of `surface` (copied).
  explicit VesselWall(const TriangleMesh& surface);
  ~VesselWall();
  VesselWall(VesselWall&&) noexcept;
  VesselWall& operator=(VesselWall&&) noexcept;

  // Distance from `p` to the nearest point of the wall.
  double distance(const Eigen::Vector3d& p) const;

  // Distance along the unit direction `d` from `origin` to the first wall hit within
  // `max_length`, or +infinity when there is none. A finite `max_length` keeps the
  // search local (a ray through a whole tree meets many far branches).
  double ray_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& d,
                 double max_length = std::numeric_limits<double>::infinity()) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gw
