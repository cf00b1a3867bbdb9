#pragma once
// Test helpers for the anatomy set: the committed index, and geometry computed
// independently of the generator (tube-union volume, point-to-mesh distance, winding number).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "base/graph/anatomy_index.hpp"
#include "base/graph/centerline_graph.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw::test {

inline std::string repo(const std::string& relative) { return std::string(GW_SOURCE_DIR) + "/" + relative; }

inline std::string scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "gw_anatomy_tests" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// anatomies/index.json through the project's one reader (every path absolute).
inline std::vector<gw::AnatomyEntry> committed_anatomies() { return gw::read_anatomy_index(repo("anatomies/index.json")); }

// ---- Reference volume of the union of tubes described by a centerline graph ----------------
// Each graph branch polyline is a chain of truncated cones (radius linear along a segment)
// with a ball at every vertex except the tree's free ends (inlet start, leaf ends), which are
// cut flat. The union's volume is estimated by stratified Monte-Carlo: the tree is cut into
// chunks of a few segments; each chunk samples its own bounding box and counts the points
// inside its tube and inside no earlier chunk's tube, so overlaps (junctions) count once.
struct TubePiece {
  Eigen::Vector3d a, b;
  double ra, rb;
  bool ball_a, ball_b;  // rounded joint at each end (false = flat free end)
};

inline bool inside_piece(const TubePiece& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d ab = s.b - s.a;
  const double t = (p - s.a).dot(ab) / ab.squaredNorm();
  if (t >= 0.0 && t <= 1.0) {
    const double r = s.ra + t * (s.rb - s.ra);
    if ((p - s.a - t * ab).squaredNorm() <= r * r) return true;
  }
  if (s.ball_a && (p - s.a).squaredNorm() <= s.ra * s.ra) return true;
  if (s.ball_b && (p - s.b).squaredNorm() <= s.rb * s.rb) return true;
  return false;
}

inline double tube_union_volume(const CenterlineGraph& g, double density = 30.0, unsigned seed = 7) {
  std::vector<char> has_child(g.branches.size(), 0);
  for (const auto& b : g.branches)
    if (b.parent >= 0) has_child[b.parent] = 1;
  struct Chunk {
    std::vector<TubePiece> pieces;
    Eigen::AlignedBox3d box;
  };
  std::vector<Chunk> chunks;
  for (const auto& b : g.branches) {
    const size_t n = b.points.size();
    for (size_t i = 0; i + 1 < n; ++i) {
      if (i % 8 == 0) chunks.emplace_back();
      TubePiece s{b.points[i], b.points[i + 1], b.radii[i], b.radii[i + 1], true, true};
      if (i == 0 && b.parent < 0) s.ball_a = false;              // inlet: flat
      if (i + 2 == n && !has_child[b.id]) s.ball_b = false;      // outlet: flat
      chunks.back().pieces.push_back(s);
      const double r = std::max(s.ra, s.rb);
      chunks.back().box.extend(s.a.cwiseMin(s.b) - Eigen::Vector3d::Constant(r));
      chunks.back().box.extend(s.a.cwiseMax(s.b) + Eigen::Vector3d::Constant(r));
    }
  }
  auto in_chunk = [](const Chunk& c, const Eigen::Vector3d& p) {
    if (!c.box.contains(p)) return false;
    for (const auto& s : c.pieces)
      if (inside_piece(s, p)) return true;
    return false;
  };
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double volume = 0.0;
  for (size_t c = 0; c < chunks.size(); ++c) {
    const Eigen::AlignedBox3d& box = chunks[c].box;
    const double box_volume = box.volume();
    const long samples = std::max(200L, static_cast<long>(box_volume * density));
    long hits = 0;
    for (long k = 0; k < samples; ++k) {
      const Eigen::Vector3d p = box.min() + (box.max() - box.min()).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
      if (!in_chunk(chunks[c], p)) continue;
      bool earlier = false;
      for (size_t e = 0; e < c && !earlier; ++e) earlier = in_chunk(chunks[e], p);
      if (!earlier) ++hits;
    }
    volume += box_volume * double(hits) / double(samples);
  }
  return volume;
}

// ---- Point-to-mesh distance and inside test ---------------------------------------------------
// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
inline Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                           const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Unsigned distance from p to the mesh surface (faces whose box is farther than `cap` skipped).
inline double distance_to_mesh(const TriangleMesh& m, const Eigen::Vector3d& p, double cap) {
  double best2 = cap * cap;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
    const Eigen::Vector3d gap = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
    if (gap.squaredNorm() >= best2) continue;
    best2 = std::min(best2, (closest_on_triangle(p, a, b, c) - p).squaredNorm());
  }
  return std::sqrt(best2);
}

// Generalised winding number (sum of signed solid angles / 4 pi): ~1 inside a closed,
// outward-oriented surface, ~0 outside.
inline double winding_number(const TriangleMesh& m, const Eigen::Vector3d& p) {
  double total = 0.0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = Eigen::Vector3d(m.V.row(m.F(f, 0))) - p, b = Eigen::Vector3d(m.V.row(m.F(f, 1))) - p,
                          c = Eigen::Vector3d(m.V.row(m.F(f, 2))) - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(num, den);
  }
  return total / (4.0 * M_PI);
}

}  // namespace gw::test
