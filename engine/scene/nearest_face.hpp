#pragma once
// The one closest-point rule of every wall query, static (wall_distance_among, vessel_scene.cpp) or
// moving (wall_distance_among_at, moving_wall.cpp): the two differ only in where a triangle's corners,
// normal and bounding sphere come from (the scene's arrays, or the motion field at time t) and in the
// early-outs that skip triangles (each proven not to change the answer); both keep the nearest
// candidate with NearestFace and turn it into a WallDistance with to_wall_distance.
#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "engine/scene/vessel_scene.hpp"

namespace gw {

// The nearest candidate so far. Inputs to offer: triangle f at `position` in the scanned list, its
// closest point c to the query point p, diff = p - c, d2 = |diff|^2 and its unit normal n. Output: true
// when it becomes the nearest: the first one within the cutoff, a clearly nearer one, or a tie (a shared
// edge or vertex: |d2 - best| <= 1e-12 (1 + best)) whose plane is more aligned with p - c (it decides the side).
struct NearestFace {
  explicit NearestFace(double cutoff) : cutoff2(cutoff * cutoff), d2(cutoff * cutoff) {}
  double cutoff2;
  double d2;          // the best squared distance (the cutoff's until a triangle is taken)
  double cos = -1;    // |cos| between p - c and the best face's normal
  int triangle = -1;  // -1: none within the cutoff
  int position = -1;  // its position in the scanned list
  Eigen::Vector3d closest = Eigen::Vector3d::Zero(), diff = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();

  bool offer(int f, int at, const Eigen::Vector3d& c, const Eigen::Vector3d& p_minus_c, double dist2,
             const Eigen::Vector3d& n) {
    const double cosv = dist2 > 0 ? std::abs(p_minus_c.dot(n)) / std::sqrt(dist2) : 1.0;
    bool better;
    if (triangle < 0)
      better = dist2 <= cutoff2;
    else if (std::abs(dist2 - d2) <= 1e-12 * (1 + d2))
      better = cosv > cos;
    else
      better = dist2 < d2;
    if (!better) return false;
    d2 = dist2;
    cos = cosv;
    triangle = f;
    position = at;
    closest = c;
    diff = p_minus_c;
    normal = n;
    return true;
  }
};

// The query's answer from the nearest face: signed distance (> 0 on the lumen side of its plane) and the
// inward direction, the Phong-interpolated vertex normal at the closest point (the face normal where the
// interpolation degenerates). Inputs: the face's corners a, b, c and normal_at(k), the unit vertex normal
// of corner k (0, 1, 2), asked only when needed. With no face within the cutoff: +inf, triangle -1.
template <class CornerNormal>
WallDistance to_wall_distance(const NearestFace& best, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, const CornerNormal& normal_at) {
  WallDistance out;
  out.signed_distance = std::numeric_limits<double>::infinity();
  if (best.triangle < 0) return out;
  out.triangle = best.triangle;
  out.closest = best.closest;
  const Eigen::Vector3d& n = best.normal;
  const double dist = std::sqrt(best.d2);
  out.signed_distance = best.diff.dot(n) <= 0 ? dist : -dist;
  // Barycentric coordinates of the closest point, then the interpolated vertex normal there.
  const Eigen::Vector3d v0 = b - a, v1 = c - a, v2 = best.closest - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  Eigen::Vector3d smooth = n;
  if (den > 0) {
    const double wb = (d11 * d20 - d01 * d21) / den, wc = (d00 * d21 - d01 * d20) / den;
    smooth = (1 - wb - wc) * normal_at(0) + wb * normal_at(1) + wc * normal_at(2);
    if (smooth.norm() > 1e-9 && smooth.dot(n) > 0) smooth.normalize();
    else smooth = n;
  }
  out.inward = -smooth;
  return out;
}

}  // namespace gw
