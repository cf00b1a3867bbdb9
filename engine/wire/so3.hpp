#pragma once
// Rotation helpers for the geometrically exact beam: hat map, exponential/logarithm and the right
// Jacobian of SO(3) (Sola, "A micro Lie theory", 2018, eq. 143-146), closed form with Taylor
// expansions near zero so derivatives stay smooth for nearly straight elements.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace gw {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

// [v]x: the cross-product matrix, [v]x w = v x w.
inline Mat3 hat(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Rotation matrix exp([phi]x).
inline Mat3 so3_exp(const Vec3& phi) {
  const double t = phi.norm();
  if (t < 1e-12) return Mat3::Identity() + hat(phi);
  return Eigen::AngleAxisd(t, phi / t).toRotationMatrix();
}

// Rotation vector of R (angle in [0, pi]).
inline Vec3 so3_log(const Mat3& r) {
  const double c = std::clamp(0.5 * (r.trace() - 1.0), -1.0, 1.0);
  const double t = std::acos(c);
  const Vec3 w(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
  if (t < 1e-6) return 0.5 * (1.0 + t * t / 6.0) * w;
  if (t < M_PI - 1e-6) return t / (2.0 * std::sin(t)) * w;
  const Eigen::AngleAxisd aa(r);  // robust near pi
  return aa.angle() * aa.axis();
}

// Right Jacobian Jr(phi): Exp(phi + d) ~ Exp(phi) Exp(Jr(phi) d).
inline Mat3 so3_right_jacobian(const Vec3& phi) {
  const double t2 = phi.squaredNorm();
  const Mat3 h = hat(phi);
  double a, b;
  if (t2 < 1e-8) {
    a = 0.5 - t2 / 24.0;
    b = 1.0 / 6.0 - t2 / 120.0;
  } else {
    const double t = std::sqrt(t2);
    a = (1.0 - std::cos(t)) / t2;
    b = (t - std::sin(t)) / (t2 * t);
  }
  return Mat3::Identity() - a * h + b * h * h;
}

// Inverse right Jacobian: Log(Exp(phi) Exp(d)) ~ phi + Jr^-1(phi) d.
inline Mat3 so3_right_jacobian_inv(const Vec3& phi) {
  const double t2 = phi.squaredNorm();
  const Mat3 h = hat(phi);
  double b;
  if (t2 < 1e-8) {
    b = 1.0 / 12.0 + t2 / 720.0;
  } else {
    const double t = std::sqrt(t2);
    b = 1.0 / t2 - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t));
  }
  return Mat3::Identity() + 0.5 * h + b * h * h;
}

}  // namespace gw
