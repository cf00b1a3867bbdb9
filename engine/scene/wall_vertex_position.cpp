// wall_vertex_position, wall_field_position (engine/scene/wall_motion.hpp).
// Inputs: the motion, the rest mesh and a vertex (or any rest point X, for the fields defined
// everywhere), a time [s]. Output: the current position X + D(X, t) [mm].
#include <Eigen/Geometry>
#include <cmath>

#include "engine/scene/wall_motion.hpp"

namespace gw {

namespace {

// D of the rigid and cardiac fields at rest point X (zero vector, exactly, when the amplitudes are).
Eigen::Vector3d field_displacement(const WallMotion& m, const Eigen::Vector3d& X, double t) {
  const double phase = cardiac_phase(m, t);
  if (m.kind == WallMotionKind::rigid) return m.velocity * t + m.amplitude * std::sin(2.0 * M_PI * phase);
  const double s = cardiac_activation(phase, m.systole_fraction);
  const Eigen::Vector3d y = X - m.centre;
  const double h = y.dot(m.axis);
  const Eigen::Vector3d radial = y - h * m.axis;
  const double theta = s * (m.twist_rad_per_mm * h + m.rotation_rad);
  const Eigen::Vector3d turned = Eigen::AngleAxisd(theta, m.axis) * ((1.0 - s * m.contraction) * radial);
  return (turned - radial) - (s * m.shortening * h) * m.axis + s * m.translation;
}

}  // namespace

bool wall_field_position(const WallMotion& m, const Eigen::Vector3d& X, double t, Eigen::Vector3d& x) {
  if (m.kind == WallMotionKind::phases) return false;
  x = X + field_displacement(m, X, t);
  return true;
}

Eigen::Vector3d wall_vertex_position(const WallMotion& m, const TriangleMesh& rest, int vertex, double t) {
  const Eigen::Vector3d X = rest.V.row(vertex).transpose();
  if (m.kind != WallMotionKind::phases) return X + field_displacement(m, X, t);
  const int n = static_cast<int>(m.frames.size());
  const double u = cardiac_phase(m, t) * n;
  const int j = std::min(static_cast<int>(std::floor(u)), n - 1);
  const double a = u - j;
  const Eigen::Vector3d d0 = m.frames[j].row(vertex).transpose(), d1 = m.frames[(j + 1) % n].row(vertex).transpose();
  return X + ((1.0 - a) * d0 + a * d1);
}

}  // namespace gw
