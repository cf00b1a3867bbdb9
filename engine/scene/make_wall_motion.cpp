// rigid_wall_motion, cardiac_wall_motion, phase_wall_motion (engine/scene/wall_motion.hpp).
// Inputs: the rest mesh (the scene's) and the motion's parameters. Output: the motion with its bounds
// (travel and Lipschitz constants) and the rest mesh data the lazy current geometry needs (faces around
// each vertex, longest edge). Throws std::invalid_argument for bad parameters.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/scene/wall_motion.hpp"

namespace gw {

namespace {

void check_timing(double bpm, double phase_offset, double systole) {
  if (!std::isfinite(bpm) || bpm < 0 || bpm > 300)
    throw std::invalid_argument("wall motion: the heart rate must be in [0, 300] bpm, got " + std::to_string(bpm));
  if (!std::isfinite(phase_offset)) throw std::invalid_argument("wall motion: the phase offset must be finite");
  if (!(systole > 0.05 && systole < 0.95))
    throw std::invalid_argument("wall motion: the systole fraction must be in (0.05, 0.95), got " +
                                std::to_string(systole));
}

// Faces around each vertex in ascending face order (the order make_vessel_scene accumulates vertex
// normals in), each face's corners in one record, the longest edge, a fresh id.
void finish_wall_motion(const TriangleMesh& rest, WallMotion& m) {
  const int nv = static_cast<int>(rest.V.rows()), nf = static_cast<int>(rest.F.rows());
  if (nv == 0 || nf == 0) throw std::invalid_argument("wall motion: the rest mesh is empty");
  m.vertices = nv;
  m.vertex_face_begin.assign(nv + 1, 0);
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) ++m.vertex_face_begin[rest.F(f, c) + 1];
  for (int i = 0; i < nv; ++i) m.vertex_face_begin[i + 1] += m.vertex_face_begin[i];
  m.face_vertices.resize(nf);
  for (int f = 0; f < nf; ++f) m.face_vertices[f] = {rest.F(f, 0), rest.F(f, 1), rest.F(f, 2)};
  m.vertex_face.assign(3 * nf, 0);
  m.vertex_corner.assign(3 * nf, 0);
  std::vector<int> fill(m.vertex_face_begin.begin(), m.vertex_face_begin.end() - 1);
  m.max_edge_mm = 0;
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) {
      const int v = rest.F(f, c);
      m.vertex_face[fill[v]] = f;
      m.vertex_corner[fill[v]++] = c;
      m.max_edge_mm = std::max(m.max_edge_mm, (rest.V.row(v) - rest.V.row(rest.F(f, (c + 1) % 3))).norm());
    }
  static std::atomic<long> next_id{1};
  m.id = next_id++;
}

}  // namespace

WallMotion rigid_wall_motion(const TriangleMesh& rest, const Eigen::Vector3d& velocity_mm_per_s,
                             const Eigen::Vector3d& amplitude_mm, double heart_rate_bpm, double phase_offset) {
  check_timing(heart_rate_bpm, phase_offset, 1.0 / 3.0);
  if (!velocity_mm_per_s.allFinite() || !amplitude_mm.allFinite())
    throw std::invalid_argument("wall motion: velocity and amplitude must be finite");
  WallMotion m;
  m.kind = WallMotionKind::rigid;
  m.heart_rate_bpm = heart_rate_bpm;
  m.phase_offset = phase_offset;
  m.velocity = velocity_mm_per_s;
  m.amplitude = amplitude_mm;
  finish_wall_motion(rest, m);
  return m;
}

WallMotion cardiac_wall_motion(const TriangleMesh& rest, const CardiacMotion& p) {
  check_timing(p.heart_rate_bpm, p.phase_offset, p.systole_fraction);
  if (!p.axis_origin.allFinite() || !p.axis_direction.allFinite() || !(p.axis_direction.norm() > 1e-12))
    throw std::invalid_argument("wall motion: the axis needs a finite origin and a non-zero direction");
  for (double v : {p.contraction_mm, p.reference_radius_mm, p.shortening_mm, p.reference_length_mm,
                   p.twist_deg_per_cm, p.rotation_deg})
    if (!std::isfinite(v)) throw std::invalid_argument("wall motion: the cardiac amplitudes must be finite");
  if (!p.translation_mm.allFinite()) throw std::invalid_argument("wall motion: the translation must be finite");
  if (p.reference_radius_mm < 0 || p.reference_length_mm < 0)
    throw std::invalid_argument("wall motion: reference radius and length must be >= 0 (0: from the mesh)");
  WallMotion m;
  m.kind = WallMotionKind::cardiac;
  m.heart_rate_bpm = p.heart_rate_bpm;
  m.systole_fraction = p.systole_fraction;
  m.phase_offset = p.phase_offset;
  m.centre = p.axis_origin;
  m.axis = p.axis_direction.normalized();
  double r_max = 0, h_max = 0;
  for (Eigen::Index i = 0; i < rest.V.rows(); ++i) {
    const Eigen::Vector3d y = rest.V.row(i).transpose() - m.centre;
    const double h = y.dot(m.axis);
    h_max = std::max(h_max, std::abs(h));
    r_max = std::max(r_max, (y - h * m.axis).norm());
  }
  const double ref_r = p.reference_radius_mm > 0 ? p.reference_radius_mm : r_max;
  const double ref_h = p.reference_length_mm > 0 ? p.reference_length_mm : h_max;
  m.contraction = p.contraction_mm != 0 ? p.contraction_mm / ref_r : 0.0;
  m.shortening = p.shortening_mm != 0 ? p.shortening_mm / ref_h : 0.0;
  if (std::abs(m.contraction) >= 0.5 || std::abs(m.shortening) >= 0.5)
    throw std::invalid_argument("wall motion: contraction and shortening must stay below half the reference "
                                "radius and length (the map stays invertible)");
  m.twist_rad_per_mm = p.twist_deg_per_cm * M_PI / 180.0 / 10.0;
  m.rotation_rad = p.rotation_deg * M_PI / 180.0;
  m.translation = p.translation_mm;
  if (p.has_fixed_point && !p.fixed_point.allFinite())
    throw std::invalid_argument("wall motion: the fixed point must be finite");
  m.has_fixed_point = p.has_fixed_point;
  m.fixed_point = p.fixed_point;
  // |x_i(s1) - x_i(s0)| <= |s1 - s0| B_i with B_i = (|rc| + |theta_i|) r_i + |as| |h_i| + |T|, theta_i the
  // end-systolic angle (a rotation by angle s theta and the scaling (1 - s rc), see wall_motion.hpp).
  auto travel_bound = [&](const Eigen::Vector3d& X) {
    const Eigen::Vector3d y = X - m.centre;
    const double h = y.dot(m.axis), r = (y - h * m.axis).norm();
    const double theta = std::abs(m.twist_rad_per_mm * h + m.rotation_rad);
    return (std::abs(m.contraction) + theta) * r + std::abs(m.shortening * h) + m.translation.norm();
  };
  m.travel_per_activation = 0;
  for (Eigen::Index i = 0; i < rest.V.rows(); ++i)
    m.travel_per_activation = std::max(m.travel_per_activation, travel_bound(rest.V.row(i).transpose()));
  if (m.has_fixed_point) m.travel_per_activation += travel_bound(m.fixed_point);
  m.radius_limit = r_max;
  m.height_limit = h_max;
  finish_wall_motion(rest, m);
  return m;
}

WallMotion phase_wall_motion(const TriangleMesh& rest, const std::vector<Eigen::MatrixX3d>& surfaces,
                             double heart_rate_bpm, double phase_offset) {
  check_timing(heart_rate_bpm, phase_offset, 1.0 / 3.0);
  if (surfaces.size() < 2) throw std::invalid_argument("wall motion: need at least two phase surfaces");
  WallMotion m;
  m.kind = WallMotionKind::phases;
  m.heart_rate_bpm = heart_rate_bpm;
  m.phase_offset = phase_offset;
  for (std::size_t j = 0; j < surfaces.size(); ++j) {
    if (surfaces[j].rows() != rest.V.rows() || !surfaces[j].allFinite())
      throw std::invalid_argument("wall motion: phase surface " + std::to_string(j) + " has " +
                                  std::to_string(surfaces[j].rows()) + " vertices (or non-finite ones), the mesh " +
                                  std::to_string(rest.V.rows()));
    m.frames.push_back(surfaces[j] - rest.V);
    m.frame_reach.push_back(m.frames.back().rowwise().norm().maxCoeff());
  }
  const std::size_t n = m.frames.size();
  for (std::size_t j = 0; j < n; ++j)
    m.frame_step.push_back((m.frames[(j + 1) % n] - m.frames[j]).rowwise().norm().maxCoeff());
  finish_wall_motion(rest, m);
  return m;
}

}  // namespace gw
