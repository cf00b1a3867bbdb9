// wall_vertex_position, wall_field_position (engine/scene/wall_motion.hpp).
// Inputs: the motion, the rest mesh and a vertex (or any rest point X, for the fields defined
// everywhere), a time [s]. Output: the current position X + D(X, t) [mm].
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "engine/scene/wall_motion.hpp"

namespace gw {

namespace {

// The cardiac map's D at rest point X and activation s.
Eigen::Vector3d cardiac_displacement(const WallMotion& m, const Eigen::Vector3d& X, double s) {
  const Eigen::Vector3d y = X - m.centre;
  const double h = y.dot(m.axis);
  const Eigen::Vector3d radial = y - h * m.axis;
  const double theta = s * (m.twist_rad_per_mm * h + m.rotation_rad);
  const Eigen::Vector3d turned = Eigen::AngleAxisd(theta, m.axis) * ((1.0 - s * m.contraction) * radial);
  return (turned - radial) - (s * m.shortening * h) * m.axis + s * m.translation;
}

}  // namespace

WallTime wall_time(const WallMotion& m, double t) {
  WallTime w;
  w.t = t;
  const double phase = cardiac_phase(m, t);
  if (m.kind == WallMotionKind::rigid) {
    w.shift = m.velocity * t + m.amplitude * std::sin(2.0 * M_PI * phase);
  } else if (m.kind == WallMotionKind::cardiac) {
    w.s = cardiac_activation(phase, m.systole_fraction);
    if (m.has_fixed_point) w.shift = cardiac_displacement(m, m.fixed_point, w.s);
  } else {
    const int n = static_cast<int>(m.frames.size());
    const double u = phase * n;
    w.j = std::min(static_cast<int>(std::floor(u)), n - 1);
    w.a = u - w.j;
  }
  return w;
}

namespace {

// D of the rigid and cardiac fields at rest point X (zero vector, exactly, when the amplitudes are).
Eigen::Vector3d field_displacement(const WallMotion& m, const Eigen::Vector3d& X, const WallTime& w) {
  if (m.kind == WallMotionKind::rigid) return w.shift;
  if (!m.has_fixed_point) return cardiac_displacement(m, X, w.s);
  return cardiac_displacement(m, X, w.s) - w.shift;
}

}  // namespace

Eigen::Vector3d wall_field_position(const WallMotion& m, const Eigen::Vector3d& X, const WallTime& at) {
  return X + field_displacement(m, X, at);
}

bool wall_field_position(const WallMotion& m, const Eigen::Vector3d& X, double t, Eigen::Vector3d& x) {
  if (m.kind == WallMotionKind::phases) return false;
  x = X + field_displacement(m, X, wall_time(m, t));
  return true;
}

Eigen::Vector3d wall_vertex_position(const WallMotion& m, const TriangleMesh& rest, int vertex, const WallTime& w) {
  const Eigen::Vector3d X = rest.V.row(vertex).transpose();
  if (m.kind != WallMotionKind::phases) return X + field_displacement(m, X, w);
  const int n = static_cast<int>(m.frames.size());
  const Eigen::Vector3d d0 = m.frames[w.j].row(vertex).transpose(), d1 = m.frames[(w.j + 1) % n].row(vertex).transpose();
  return X + ((1.0 - w.a) * d0 + w.a * d1);
}

Eigen::Vector3d wall_vertex_position(const WallMotion& m, const TriangleMesh& rest, int vertex, double t) {
  return wall_vertex_position(m, rest, vertex, wall_time(m, t));
}

}  // namespace gw
