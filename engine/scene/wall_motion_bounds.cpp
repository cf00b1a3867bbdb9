// wall_max_displacement, wall_max_travel, rest_query_ball (engine/scene/wall_motion.hpp).
// Inputs: the motion, times [s]; for the query a current point p and radius r [mm]. Outputs: upper
// bounds over the vertices of |D(t)| and |x(t1) - x(t0)| [mm]; a rest-configuration ball (centre,
// radius) holding every rest triangle whose current triangle comes within r of p.
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/scene/wall_motion.hpp"

namespace gw {

namespace {

const double kRounding = 1e-8;  // mm: floating-point slack of X + D against the exact bounds
const double kNewtonTolerance = 1e-6;  // mm: wall_rest_point's pre-image residual (enters the bounds)

Eigen::Vector3d rigid_displacement(const WallMotion& m, double t) {
  return m.velocity * t + m.amplitude * std::sin(2.0 * M_PI * cardiac_phase(m, t));
}

// Jacobian of the cardiac map x(X) at activation s (see rest_query_ball); `radial` gets y_r.
Eigen::Matrix3d cardiac_jacobian(const WallMotion& m, const Eigen::Vector3d& X, double s, Eigen::Vector3d& radial) {
  const Eigen::Vector3d y = X - m.centre;
  const double h = y.dot(m.axis);
  radial = y - h * m.axis;
  const double theta = s * (m.twist_rad_per_mm * h + m.rotation_rad);
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(theta, m.axis).toRotationMatrix();
  const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - m.axis * m.axis.transpose();
  const Eigen::Vector3d q = rot * ((1.0 - s * m.contraction) * radial);
  return (1.0 - s * m.contraction) * rot * proj + (1.0 - s * m.shortening) * m.axis * m.axis.transpose() +
         (s * m.twist_rad_per_mm) * m.axis.cross(q) * m.axis.transpose();
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

bool wall_rest_point(const WallMotion& m, const Eigen::Vector3d& p, const WallTime& at, const Eigen::Vector3d* guess,
                     RestPoint& out) {
  if (m.kind == WallMotionKind::phases) return false;
  const double half_dd = 0.5 * m.max_edge_mm * m.max_edge_mm;
  if (m.kind == WallMotionKind::rigid) {  // a translation: sigma 1, no curvature
    out.X = p - at.shift;
    out.sigma = 1;
    out.curvature = 0;
    out.slack = (wall_field_position(m, out.X, at) - p).norm() + kRounding;
    out.global = at.shift.norm() + kRounding + (p - out.X).norm();
    return true;
  }
  // Cardiac: Newton on x(X) = p from the guess (one step from a nearby time's pre-image), else from
  // p - D(p). The residual e is measured, never assumed: it enters the bounds.
  const double s = at.s;
  Eigen::Vector3d X = guess ? *guess : Eigen::Vector3d(p - (wall_field_position(m, p, at) - p));
  Eigen::Vector3d r = wall_field_position(m, X, at) - p;
  Eigen::Vector3d radial;
  // Stopped at a nanometre: the residual e is added to the bounds below (slack), next to the map's own
  // K d^2 / 2 (micrometres for the coronary field), so iterating on to rounding changes no answer and
  // would cost a second Jacobian and field evaluation in most queries.
  const double tolerance = std::max(kNewtonTolerance, 1e-11 * (1.0 + p.norm()));
  for (int it = 0; it < 8 && r.norm() > tolerance; ++it) {
    X -= cardiac_jacobian(m, X, s, radial).partialPivLu().solve(r);
    r = wall_field_position(m, X, at) - p;
  }
  const double e = r.norm();
  if (!std::isfinite(e)) return false;
  const Eigen::Vector3d y = X - m.centre;
  const double yr = (y - y.dot(m.axis) * m.axis).norm();
  // J = R(theta) [(1 - s rc) P + (1 - s as) a a^T] + s twist (a x q) a^T, |q| = |1 - s rc| |y_r|: the
  // bracket's singular values are |1 - s rc| (twice) and |1 - s as|, the last term's norm
  // |s twist| |1 - s rc| |y_r| (Weyl's inequality).
  const double scale = std::abs(1.0 - s * m.contraction);
  const double st = s * std::abs(m.twist_rad_per_mm);
  out.X = X;
  out.sigma = std::min(scale, std::abs(1.0 - s * m.shortening)) - st * scale * yr;
  out.curvature = 1.5 * st * (1.0 + st * std::max(m.radius_limit, yr));  // as in rest_query_ball
  out.slack = e + out.curvature * half_dd + kRounding;
  out.global = s * m.travel_per_activation + kRounding + out.curvature * half_dd + (p - X).norm();
  return true;
}

double rest_reach(const RestPoint& rp, double r) {
  const double inf = std::numeric_limits<double>::infinity();
  if (!(rp.sigma > 0.1) || !std::isfinite(r)) return inf;
  const double rho = std::max(0.0, r) + rp.slack;
  double z1;
  if (rp.curvature == 0) {
    z1 = rho / rp.sigma;
  } else {
    const double disc = rp.sigma * rp.sigma - 2.0 * rp.curvature * rho;
    if (!(disc > 0)) return inf;
    const double root = std::sqrt(disc);
    if (!((rp.sigma + root) / rp.curvature > r + rp.global)) return inf;  // z2 not ruled out
    z1 = 2.0 * rho / (rp.sigma + root);
  }
  return z1 * (1.0 + 1e-12) + kRounding;
}

double current_reach(const RestPoint& rp, double z) {
  if (!(rp.sigma > 0.1) || !(z > 2 * kRounding)) return 0;
  double zc = z - 2 * kRounding;
  if (rp.curvature > 0) zc = std::min(zc, rp.sigma / rp.curvature);
  const double delta = (rp.sigma * zc - 0.5 * rp.curvature * zc * zc - rp.slack) * (1.0 - 1e-12);
  if (!(delta > 0) || !(rest_reach(rp, delta) <= z)) return 0;
  return delta;
}

void rest_query_ball(const WallMotion& m, const Eigen::Vector3d& p, double r, double t, Eigen::Vector3d& centre,
                     double& radius) {
  if (m.kind == WallMotionKind::rigid) {  // a translation: pulled back exactly
    centre = p - rigid_displacement(m, t);
    radius = r + kRounding;
    return;
  }
  if (m.kind == WallMotionKind::cardiac) {
    // Pull p back: X* with x(X*) = p by Newton's method, e = |x(X*) - p|. The map x = X + D has the
    // Jacobian J(X) = R(theta)(1 - s rc) P + (1 - s as) a a^T + s twist (a x q) a^T (P = I - a a^T,
    // q = R(theta)(1 - s rc) y_r) and second derivatives bounded by K = 1.5 s twist (1 + s twist r)
    // (only the twist bends the map; |rc| < 0.5). A current triangle point y = sum w_i x(X_i) within r of
    // p: its rest point Y = sum w_i X_i has |x(Y) - y| <= K d^2 / 2 (linear interpolation, d the longest
    // edge), so |x(Y) - x(X*)| <= rho = r + e + K d^2 / 2, while |x(Y) - x(X*)| >= sigma z - K z^2 / 2
    // (z = |Y - X*|, sigma the smallest singular value of J(X*)). Hence z <= z1 or z >= z2, the roots of
    // K z^2 / 2 - sigma z + rho; z2 beyond the global bound r + |p - X*| + max |D| leaves z <= z1.
    const double s = activation(m, t);
    Eigen::Vector3d X = p, x;
    Eigen::Vector3d radial;
    Eigen::Matrix3d jac;
    wall_field_position(m, X, t, x);
    X = p - (x - p);  // X - D(X) ~ the inverse; then Newton steps
    for (int it = 0; it < 5; ++it) {
      wall_field_position(m, X, t, x);
      jac = cardiac_jacobian(m, X, s, radial);
      if ((x - p).norm() < 1e-12) break;
      X -= jac.partialPivLu().solve(x - p);
    }
    wall_field_position(m, X, t, x);
    jac = cardiac_jacobian(m, X, s, radial);
    const double e = (x - p).norm();
    const double sigma = Eigen::JacobiSVD<Eigen::Matrix3d>(jac).singularValues()(2);
    const double st = s * std::abs(m.twist_rad_per_mm);
    const double K = 1.5 * st * (1.0 + st * std::max(m.radius_limit, radial.norm()));
    const double rho = r + e + 0.5 * K * m.max_edge_mm * m.max_edge_mm;
    const double global = r + (p - X).norm() + wall_max_displacement(m, t);
    if (std::isfinite(e) && sigma > 0.1) {
      if (K == 0) {
        centre = X;
        radius = rho / sigma + kRounding;
        return;
      }
      const double disc = sigma * sigma - 2.0 * K * rho;
      if (disc > 0 && (sigma + std::sqrt(disc)) / K > global) {
        centre = X;
        radius = std::min(global, (sigma - std::sqrt(disc)) / K) + kRounding;
        return;
      }
    }
  }
  centre = p;  // the global bound: every vertex moved at most max |D|
  radius = r + wall_max_displacement(m, t);
}

}  // namespace gw
