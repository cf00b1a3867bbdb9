// wall_max_displacement, wall_max_travel, rest_query_ball (engine/scene/wall_motion.hpp).
// Inputs: the motion, times [s]; for the query a current point p and radius r [mm]. Outputs: upper
// bounds over the vertices of |D(t)| and |x(t1) - x(t0)| [mm]; a rest-configuration ball (centre,
// radius) holding every rest triangle whose current triangle comes within r of p.
#include <algorithm>
#include <cmath>

#include "engine/scene/wall_motion.hpp"

namespace gw {

namespace {

const double kRounding = 1e-8;  // mm: floating-point slack of X + D against the exact bounds

Eigen::Vector3d rigid_displacement(const WallMotion& m, double t) {
  return m.velocity * t + m.amplitude * std::sin(2.0 * M_PI * cardiac_phase(m, t));
}

double activation(const WallMotion& m, double t) {
  return cardiac_activation(cardiac_phase(m, t), m.systole_fraction);
}

// Phase-surface travel bound walking the frames from u0 up to u1 (u1 >= u0, in frame units, u0 in [0, N)).
double frames_walk(const WallMotion& m, double u0, double u1) {
  const int n = static_cast<int>(m.frames.size());
  double sum = 0;
  for (double u = u0; u < u1;) {
    const double j = std::floor(u);
    const double next = std::min(u1, j + 1);
    sum += (next - u) * m.frame_step[static_cast<int>(j) % n];
    u = next;
  }
  return sum;
}

}  // namespace

double wall_max_displacement(const WallMotion& m, double t) {
  switch (m.kind) {
    case WallMotionKind::rigid:
      return rigid_displacement(m, t).norm() + kRounding;
    case WallMotionKind::cardiac:
      return activation(m, t) * m.travel_per_activation + kRounding;
    case WallMotionKind::phases: {
      const int n = static_cast<int>(m.frames.size());
      const double u = cardiac_phase(m, t) * n;
      const int j = std::min(static_cast<int>(std::floor(u)), n - 1);
      const double a = u - j;
      return (1 - a) * m.frame_reach[j] + a * m.frame_reach[(j + 1) % n] + kRounding;
    }
  }
  return 0;
}

double wall_max_travel(const WallMotion& m, double t0, double t1) {
  if (t0 == t1) return 0;
  switch (m.kind) {
    case WallMotionKind::rigid:
      return (rigid_displacement(m, t1) - rigid_displacement(m, t0)).norm() + kRounding;
    case WallMotionKind::cardiac:
      return std::abs(activation(m, t1) - activation(m, t0)) * m.travel_per_activation + kRounding;
    case WallMotionKind::phases: {
      const int n = static_cast<int>(m.frames.size());
      const double u0 = cardiac_phase(m, t0) * n, u1 = cardiac_phase(m, t1) * n;
      const double forward = frames_walk(m, u0, u1 >= u0 ? u1 : u1 + n);
      const double backward = frames_walk(m, u1, u0 >= u1 ? u0 : u0 + n);
      const double reach = *std::max_element(m.frame_reach.begin(), m.frame_reach.end());
      return std::min({forward, backward, 2 * reach}) + kRounding;
    }
  }
  return 0;
}

void rest_query_ball(const WallMotion& m, const Eigen::Vector3d& p, double r, double t, Eigen::Vector3d& centre,
                     double& radius) {
  if (m.kind == WallMotionKind::rigid) {  // a translation: pulled back exactly
    centre = p - rigid_displacement(m, t);
    radius = r + kRounding;
    return;
  }
  if (m.kind == WallMotionKind::cardiac) {
    // x = X + D(X) with |D(X) - D(Y)| <= L |X - Y| (L = s L1 < 1) inside the cylinder of the vertices.
    // X* = p - D(X*) by fixed-point iteration, e = |X* + D(X*) - p|. A current triangle point
    // y = sum w_i x_i within r of p has its rest point Y = sum w_i X_i within
    // (r + e + L max_edge) / (1 - L) of X*: |Y - X*| <= |y - p| + e + L sum w_i |X_i - X*|.
    const double L = activation(m, t) * m.lipschitz_per_activation;
    if (L < 0.5) {
      Eigen::Vector3d X = p, x;
      for (int it = 0; it < 4; ++it) {
        wall_field_position(m, X, t, x);
        X -= x - p;
      }
      wall_field_position(m, X, t, x);
      const double e = (x - p).norm();
      const Eigen::Vector3d y = X - m.centre;
      const double h = y.dot(m.axis);
      if (std::abs(h) <= m.height_limit && (y - h * m.axis).norm() <= m.radius_limit) {
        centre = X;
        radius = (r + e + L * m.max_edge_mm) / (1 - L) + kRounding;
        return;
      }
    }
  }
  centre = p;  // the global bound: every vertex moved at most max |D|
  radius = r + wall_max_displacement(m, t);
}

}  // namespace gw
