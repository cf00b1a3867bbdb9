#pragma once
// wall_distance through the uniform grid instead of FCL's BVH queries.
#include <Eigen/Core>

#include "engine/scene/vessel_scene.hpp"

namespace gw {

// Inputs: `scene` (static wall, or a moving wall's rest mesh), point `p`, `radius` > 0 a first search
// radius (e.g. a distance within which the wall is known to be absent: the search starts at twice it).
// Output: the closest wall point to p, as wall_distance: every triangle whose bounding sphere comes
// within the search radius of p (triangles_near) is scanned by wall_distance_among with that radius as
// the cutoff; none within it: the radius doubles. The first radius that holds a triangle holds the
// nearest one (a superset of the triangles within it was scanned). Its two FCL queries cost ~100x more
// (they were a quarter of a coronary insertion's time, asked for points far from the wall).
WallDistance wall_distance_by_grid(const VesselScene& scene, const Eigen::Vector3d& p, double radius);

}  // namespace gw
