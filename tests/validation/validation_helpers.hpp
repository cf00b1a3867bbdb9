#pragma once
// Shared set-ups of the validation suite (tests/validation): clamped beams, a closed box whose floor is
// a flat plane, a bent tube, and the wire laid along a centreline. Every reference the tests compare
// with is written in the test itself, not here.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <tuple>
#include <map>
#include <vector>

#include "base/mesh/triangle_mesh.hpp"
#include "engine/scene/swept_tube_mesh.hpp"
#include "engine/scene/vessel_scene.hpp"
#include "engine/sim/step.hpp"
#include "engine/wire/beam_element.hpp"
#include "engine/wire/wire_model.hpp"
#include "engine/wire/wire_state.hpp"
#include "../engine/mechanics_helpers.hpp"

namespace gw::validation {

// test::uniform_beam_params (a uniform straight beam of `length_mm`, elements of `element_mm`) with no
// Rayleigh damping and one integration sub-step of at most `h` per step.
inline WireParams beam_params(double length_mm, double element_mm, double h) {
  WireParams p = test::uniform_beam_params(length_mm, element_mm);
  p.damping_mass = 0;
  p.damping_stiffness = 0;
  p.max_substep_s = h;
  return p;
}

// Adaptive stepping (WireParams::max_free_substep_s, issue 62): the physics tests run at both settings, every
// sub-step the test's own (span 1), and sub-steps `span` times as long wherever the wire meets no wall.
inline WireParams with_free_span(WireParams p, int span) {
  p.max_free_substep_s = span > 1 ? span * p.max_substep_s : 0;
  return p;
}

// Mass per length rho A of the model's wire [kg/mm].
inline double mass_per_length(const WireModel& m) {
  return m.params.density_kg_per_mm3 * M_PI * m.radius_mm * m.radius_mm;
}

// Mode shape n (0-based) of a clamped-free Euler-Bernoulli beam of length L at distance s from the
// clamp, with beta_n L = 1.87510, 4.69409, 7.85476 (roots of cos(bL) cosh(bL) = -1):
// phi = cosh(bs) - cos(bs) - sigma (sinh(bs) - sin(bs)), sigma = (cosh bL + cos bL) / (sinh bL + sin bL).
inline double clamped_free_mode(int n, double s, double length, double* slope = nullptr) {
  static const double kBetaL[3] = {1.87510407, 4.69409113, 7.85475744};
  const double b = kBetaL[n] / length, bl = kBetaL[n];
  const double sigma = (std::cosh(bl) + std::cos(bl)) / (std::sinh(bl) + std::sin(bl));
  if (slope)
    *slope = b * (std::sinh(b * s) + std::sin(b * s) - sigma * (std::cosh(b * s) - std::cos(b * s)));
  return std::cosh(b * s) - std::cos(b * s) - sigma * (std::sinh(b * s) - std::sin(b * s));
}

// Axial force of element e (EA times the stretch strain) [mN]; positive in tension.
inline double axial_force(const WireModel& m, const WireState& s, int e) {
  BeamElementEval ev;
  eval_beam_element(m, e, s.x[e], s.q[e].toRotationMatrix(), s.x[e + 1], s.q[e + 1].toRotationMatrix(), ev);
  return m.stiffness[e][0] * ev.strain[0];
}

// A closed box [lo, hi] whose every face is an n x n grid of squares (so the floor's inner vertices
// have exactly the floor's normal and a wire lying there sees a flat plane); outward faces.
inline TriangleMesh grid_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n) {
  TriangleMesh m;
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  std::map<std::tuple<long, long, long>, int> index;
  auto vertex = [&](const Eigen::Vector3d& p) {
    const auto key = std::make_tuple(std::lround(p.x() * 1e6), std::lround(p.y() * 1e6), std::lround(p.z() * 1e6));
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    v.push_back(p);
    index[key] = static_cast<int>(v.size()) - 1;
    return static_cast<int>(v.size()) - 1;
  };
  // Each face: axis k fixed at lo or hi; (a, b) the other two axes ordered so a x b is outward.
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      int a = (k + 1) % 3, b = (k + 2) % 3;
      if (side == 0) std::swap(a, b);  // outward is -k: reverse the winding
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto corner = [&](int ii, int jj) {
            Eigen::Vector3d p;
            p[k] = side ? hi[k] : lo[k];
            p[a] = lo[a] + (hi[a] - lo[a]) * ii / n;
            p[b] = lo[b] + (hi[b] - lo[b]) * jj / n;
            return vertex(p);
          };
          const int c00 = corner(i, j), c10 = corner(i + 1, j), c11 = corner(i + 1, j + 1), c01 = corner(i, j + 1);
          f.emplace_back(c00, c10, c11);
          f.emplace_back(c00, c11, c01);
        }
    }
  m.V.resize(v.size(), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.V.row(i) = v[i].transpose();
  m.F.resize(f.size(), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.F.row(i) = f[i].transpose();
  return m;
}

// A centreline sampled every `ds` mm: straight pieces and circular arcs, each given as (length, or
// arc angle [rad] with radius and the axis it turns about, in the current local frame).
struct PathPiece {
  double length = 0;      // straight length [mm] (arcs: 0)
  double angle = 0;       // arc angle [rad]
  double radius = 0;      // arc radius [mm]
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // arc rotation axis, world frame, perpendicular to the heading
};

struct Path {
  std::vector<Eigen::Vector3d> points, tangents;
  std::vector<Eigen::Quaterniond> turns;  // rotation from the start's frame (parallel transport: no twist)
};

inline Path sample_path(const Eigen::Vector3d& start, const Eigen::Vector3d& heading,
                        const std::vector<PathPiece>& pieces, double ds) {
  Path p;
  Eigen::Vector3d x = start, t = heading.normalized();
  Eigen::Quaterniond turn = Eigen::Quaterniond::Identity();
  p.points.push_back(x);
  p.tangents.push_back(t);
  p.turns.push_back(turn);
  for (const PathPiece& piece : pieces) {
    if (piece.angle == 0) {
      const int k = std::max(1, static_cast<int>(std::ceil(piece.length / ds)));
      for (int i = 0; i < k; ++i) {
        x += (piece.length / k) * t;
        p.points.push_back(x);
        p.tangents.push_back(t);
        p.turns.push_back(turn);
      }
    } else {
      const Eigen::Vector3d axis = piece.axis.normalized();
      const Eigen::Vector3d centre = x + piece.radius * axis.cross(t);
      const Eigen::Vector3d arm = x - centre;
      const int k = std::max(1, static_cast<int>(std::ceil(piece.radius * piece.angle / ds)));
      for (int i = 1; i <= k; ++i) {
        const Eigen::AngleAxisd r(piece.angle * i / k, axis);
        p.points.push_back(centre + r * arm);
        p.tangents.push_back(r * t);
        p.turns.push_back((Eigen::Quaterniond(r) * turn).normalized());
      }
      x = p.points.back();
      t = p.tangents.back();
      turn = p.turns.back();
    }
  }
  return p;
}

inline VesselScene tube_scene(const Path& path, double radius) {
  Eigen::MatrixX3d c(path.points.size(), 3);
  for (std::size_t i = 0; i < path.points.size(); ++i) c.row(i) = path.points[i].transpose();
  return make_vessel_scene(swept_tube_mesh(c, radius, 32));
}

// Point, tangent and turn of the path at arc length s (linear / slerp between samples).
inline void path_at(const Path& p, double s, Eigen::Vector3d& x, Eigen::Vector3d& t, Eigen::Quaterniond& turn) {
  double acc = 0;
  for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
    const double seg = (p.points[i + 1] - p.points[i]).norm();
    if (s <= acc + seg || i + 2 == p.points.size()) {
      const double a = std::clamp((s - acc) / seg, 0.0, 1.0);
      x = (1 - a) * p.points[i] + a * p.points[i + 1];
      t = ((1 - a) * p.tangents[i] + a * p.tangents[i + 1]).normalized();
      turn = p.turns[i].slerp(a, p.turns[i + 1]);
      return;
    }
    acc += seg;
  }
  x = p.points.back();
  t = p.tangents.back();
  turn = p.turns.back();
}

// Lays the free part of the wire along the path (node at arc a from the inlet on the path's point at
// a), frames the introducer's carried along the path by parallel transport (no twist). The path must
// start at the inlet along the inlet direction.
inline void lay_along(const WireModel& m, WireState& s, const Path& path) {
  const int k = first_free_node(m, s);
  for (int i = k; i < m.nodes; ++i) {
    Eigen::Vector3d x, t;
    Eigen::Quaterniond turn;
    path_at(path, s.inserted_length_mm - m.arc_from_tip[i], x, t, turn);
    s.x[i] = x;
    s.q[i] = (turn * introducer_frame(s)).normalized();
    s.v[i].setZero();
    s.w[i].setZero();
  }
}

}  // namespace gw::validation
