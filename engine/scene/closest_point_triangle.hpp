#pragma once
// Closest point on a triangle (Ericson, "Real-Time Collision Detection", 5.1.5).
#include <Eigen/Core>

namespace gw {

// Closest point to `p` on triangle (a, b, c); `region` is 0 for the face interior, 1 for an edge or
// vertex (where the face normal alone does not decide the side).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c, int& region);

}  // namespace gw
