#include "task/polyline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gw {

Polyline make_polyline(const std::vector<Eigen::Vector3d>& points) {
  Polyline line;
  line.points.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) throw std::invalid_argument("polyline has a non-finite point");
    if (!line.points.empty() && (p - line.points.back()).norm() < 1e-9) continue;
    line.points.push_back(p);
  }
  const size_t n = line.points.size();
  if (n < 2) throw std::invalid_argument("polyline needs at least two distinct points");
  line.arc.resize(n);
  line.arc[0] = 0.0;
  for (size_t i = 1; i < n; ++i) line.arc[i] = line.arc[i - 1] + (line.points[i] - line.points[i - 1]).norm();
  line.length = line.arc.back();
  line.tangents.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const size_t a = i == 0 ? 0 : i - 1;
    const size_t b = i + 1 == n ? n - 1 : i + 1;
    line.tangents[i] = (line.points[b] - line.points[a]).normalized();
  }
  return line;
}

PolylineProjection project_onto_polyline(const Polyline& line, const Eigen::Vector3d& p, int first_segment,
                                         int last_segment) {
  const int segments = static_cast<int>(line.points.size()) - 1;
  if (last_segment < 0 || last_segment >= segments) last_segment = segments - 1;
  first_segment = std::clamp(first_segment, 0, last_segment);
  PolylineProjection best;
  double best_d2 = INFINITY;
  for (int s = first_segment; s <= last_segment; ++s) {
    const Eigen::Vector3d& a = line.points[s];
    const Eigen::Vector3d ab = line.points[s + 1] - a;
    const double len2 = ab.squaredNorm();
    const double u = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
    const double d2 = (a + u * ab - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best.segment = s;
      best.arc = line.arc[s] + u * (line.arc[s + 1] - line.arc[s]);
    }
  }
  best.distance = std::sqrt(best_d2);
  return best;
}

int polyline_segment_at(const Polyline& line, double arc) {
  const int segments = static_cast<int>(line.points.size()) - 1;
  const auto it = std::upper_bound(line.arc.begin(), line.arc.end(), arc);
  const int s = static_cast<int>(it - line.arc.begin()) - 1;
  return std::clamp(s, 0, segments - 1);
}

Eigen::Vector3d polyline_point(const Polyline& line, double arc) {
  arc = std::clamp(arc, 0.0, line.length);
  const int s = polyline_segment_at(line, arc);
  const double u = (arc - line.arc[s]) / (line.arc[s + 1] - line.arc[s]);
  return line.points[s] + u * (line.points[s + 1] - line.points[s]);
}

Eigen::Vector3d polyline_tangent(const Polyline& line, double arc) {
  arc = std::clamp(arc, 0.0, line.length);
  const int s = polyline_segment_at(line, arc);
  const double u = (arc - line.arc[s]) / (line.arc[s + 1] - line.arc[s]);
  const Eigen::Vector3d t = (1.0 - u) * line.tangents[s] + u * line.tangents[s + 1];
  const double n = t.norm();
  // Opposite neighbouring tangents (a hairpin) would cancel: fall back to the segment direction.
  return n > 1e-9 ? Eigen::Vector3d(t / n) : Eigen::Vector3d((line.points[s + 1] - line.points[s]).normalized());
}

}  // namespace gw
