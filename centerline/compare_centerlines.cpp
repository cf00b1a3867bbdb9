#include "centerline/compare_centerlines.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

namespace gw {
namespace {

struct Nearest {
  double distance = std::numeric_limits<double>::infinity();
  double radius = 0.0;  // true radius interpolated at the nearest location
};

// Nearest point over every segment of every truth branch (brute force: a few thousand
// points against a few thousand segments is milliseconds).
Nearest nearest_on_truth(const CenterlineGraph& truth, const Eigen::Vector3d& p) {
  Nearest best;
  for (const auto& b : truth.branches) {
    if (b.points.size() == 1) {
      const double d = (p - b.points[0]).norm();
      if (d < best.distance) best = {d, b.radii[0]};
    }
    for (size_t i = 1; i < b.points.size(); ++i) {
      const Eigen::Vector3d a = b.points[i - 1], e = b.points[i] - a;
      const double len2 = e.squaredNorm();
      const double t = len2 > 0 ? std::clamp((p - a).dot(e) / len2, 0.0, 1.0) : 0.0;
      const double d = (p - (a + t * e)).norm();
      if (d < best.distance) best = {d, (1 - t) * b.radii[i - 1] + t * b.radii[i]};
    }
  }
  return best;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double idx = q * double(v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(idx)), hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (idx - double(lo)) * (v[hi] - v[lo]);
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

std::vector<Terminal> terminals_of(const CenterlineGraph& g) {
  std::vector<Terminal> t{g.inlet};
  t.insert(t.end(), g.targets.begin(), g.targets.end());
  return t;
}

}  // namespace

CenterlineAccuracy compare_centerlines(const CenterlineGraph& ex, const CenterlineGraph& truth) {
  if (ex.branches.empty() || truth.branches.empty())
    throw std::invalid_argument("compare_centerlines: both graphs need at least one branch");
  for (const auto& b : truth.branches)
    if (b.points.empty() || b.radii.size() != b.points.size())
      throw std::invalid_argument("compare_centerlines: truth branch " + std::to_string(b.id) + " has no points or radii");
  CenterlineAccuracy a;
  std::vector<double> dist, rad;
  for (const auto& b : ex.branches) {
    // A child's first point is its parent's last: count shared points once.
    for (size_t i = b.parent >= 0 ? 1 : 0; i < b.points.size(); ++i) {
      const Nearest n = nearest_on_truth(truth, b.points[i]);
      if (!(n.radius > 0)) continue;
      dist.push_back(n.distance / n.radius);
      if (i < b.radii.size()) rad.push_back(std::abs(b.radii[i] - n.radius) / n.radius);
    }
  }
  a.points = static_cast<long>(dist.size());
  a.mean_distance = mean(dist);
  a.p95_distance = percentile(dist, 0.95);
  a.max_distance = dist.empty() ? 0.0 : *std::max_element(dist.begin(), dist.end());
  a.mean_radius_error = mean(rad);
  a.p95_radius_error = percentile(rad, 0.95);

  for (const auto& tb : truth.bifurcations) {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& eb : ex.bifurcations) d = std::min(d, (eb.position - tb.position).norm());
    // "Within one radius" of the vessel that divides: the parent's radius at its end.
    double r = nearest_on_truth(truth, tb.position).radius;
    if (tb.parent >= 0 && tb.parent < static_cast<int>(truth.branches.size()) && !truth.branches[tb.parent].radii.empty())
      r = truth.branches[tb.parent].radii.back();
    a.max_bifurcation_offset = std::max(a.max_bifurcation_offset, r > 0 ? d / r : d);
  }
  a.bifurcations = static_cast<int>(ex.bifurcations.size());
  a.true_bifurcations = static_cast<int>(truth.bifurcations.size());

  const auto et = terminals_of(ex), tt = terminals_of(truth);
  a.terminals = static_cast<int>(et.size());
  a.true_terminals = static_cast<int>(tt.size());
  bool matched_all = true;
  std::vector<char> taken(et.size(), 0);
  for (const auto& t : tt) {
    const double r = std::max(t.radius, nearest_on_truth(truth, t.position).radius);
    int best = -1;
    for (size_t i = 0; i < et.size(); ++i)
      if (!taken[i] && (best < 0 || (et[i].position - t.position).norm() < (et[best].position - t.position).norm()))
        best = static_cast<int>(i);
    const double d = best >= 0 ? (et[best].position - t.position).norm() : std::numeric_limits<double>::infinity();
    if (best >= 0) taken[best] = 1;
    a.max_terminal_offset = std::max(a.max_terminal_offset, r > 0 ? d / r : d);
    if (!(d <= 2.0 * r)) matched_all = false;
  }
  a.same_topology = matched_all && a.terminals == a.true_terminals && a.bifurcations == a.true_bifurcations;
  return a;
}

std::string accuracy_to_json(const CenterlineAccuracy& a) {
  nlohmann::json j = {{"same_topology", a.same_topology},
                      {"terminals", a.terminals},
                      {"true_terminals", a.true_terminals},
                      {"bifurcations", a.bifurcations},
                      {"true_bifurcations", a.true_bifurcations},
                      {"points", a.points},
                      {"mean_distance_over_radius", a.mean_distance},
                      {"p95_distance_over_radius", a.p95_distance},
                      {"max_distance_over_radius", a.max_distance},
                      {"mean_radius_error", a.mean_radius_error},
                      {"p95_radius_error", a.p95_radius_error},
                      {"max_bifurcation_offset_over_radius", a.max_bifurcation_offset},
                      {"max_terminal_offset_over_radius", a.max_terminal_offset}};
  return j.dump();
}

}  // namespace gw
