#include "anatomy_gen/tube_field.hpp"

#include <algorithm>
#include <cmath>

namespace gw {
namespace {

// Polynomial smooth minimum (Quilez): equals min(a,b) when |a-b| >= k, and rounds the
// corner by at most k/4 where the two tubes meet.
double smooth_min(double a, double b, double k) {
  if (k <= 0.0) return std::min(a, b);
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - 0.25 * h * h * k;
}

}  // namespace

TubeField::TubeField(const TreeGeometry& g)
    : blend_(g.blend), max_radius_(g.max_radius), branches_(static_cast<int>(g.branches.size())) {
  start_cap_.resize(branches_);
  end_cap_.resize(branches_);
  for (int b = 0; b < branches_; ++b) {
    const BranchCurve& c = g.branches[b];
    const size_t n = c.points.size();
    const double length = c.arclength.back();
    const Eigen::Vector3d n0 = (c.points[0] - c.points[1]).normalized();
    const Eigen::Vector3d n1 = (c.points[n - 1] - c.points[n - 2]).normalized();
    start_cap_[b] = {c.points[0], n0};
    end_cap_[b] = {c.points[n - 1], n1};
    // A capped end's zone: the last two radii of the tube plus a straight extension beyond
    // the cap plane, so the clipped tube ends in an exact flat disc.
    const double zone0 = c.cap_start ? 2.0 * c.radii.front() : -1.0;
    const double zone1 = c.cap_end ? length - 2.0 * c.radii.back() : INFINITY;
    if (c.cap_start)
      segments_.push_back({c.points[0] + 2.0 * c.radii[0] * n0, c.points[0], c.radii[0], c.radii[0], b, 1});
    for (size_t i = 0; i + 1 < n; ++i) {
      const double mid = 0.5 * (c.arclength[i] + c.arclength[i + 1]);
      int group = 0;
      if (mid < zone0 && (mid < length - mid || !c.cap_end)) group = 1;
      else if (mid > zone1) group = 2;
      segments_.push_back({c.points[i], c.points[i + 1], c.radii[i], c.radii[i + 1], b, group});
    }
    if (c.cap_end)
      segments_.push_back({c.points[n - 1], c.points[n - 1] + 2.0 * c.radii.back() * n1, c.radii.back(), c.radii.back(), b, 2});
  }
  // Grid: cells about one radius wide, over the tubes plus the blend reach.
  const double reach = max_radius_ * (1.0 + blend_) + 0.2;
  cell_ = std::clamp(max_radius_, 0.5, 4.0);
  origin_ = g.bbox_min - Eigen::Vector3d::Constant(reach + cell_);
  Eigen::Vector3d extent = g.bbox_max - g.bbox_min + Eigen::Vector3d::Constant(2.0 * (reach + cell_));
  for (;;) {
    dims_ = (extent / cell_).array().ceil().cast<int>();
    if (double(dims_.x()) * dims_.y() * dims_.z() < 8e6) break;
    cell_ *= 1.5;
  }
  const long cells = long(dims_.x()) * dims_.y() * dims_.z();
  std::vector<int> count(cells + 1, 0);
  auto range = [&](const Segment& s, Eigen::Vector3i& lo, Eigen::Vector3i& hi) {
    const double r = std::max(s.ra, s.rb) * (1.0 + blend_) + 0.2;
    const Eigen::Vector3d mn = s.a.cwiseMin(s.b) - Eigen::Vector3d::Constant(r) - origin_;
    const Eigen::Vector3d mx = s.a.cwiseMax(s.b) + Eigen::Vector3d::Constant(r) - origin_;
    lo = (mn / cell_).array().floor().cast<int>().max(0);
    hi = (mx / cell_).array().floor().cast<int>().min(dims_.array() - 1);
  };
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      cell_start_.assign(cells + 1, 0);
      for (long c = 0; c < cells; ++c) cell_start_[c + 1] = cell_start_[c] + count[c];
      cell_items_.assign(cell_start_.back(), 0);
      std::fill(count.begin(), count.end(), 0);
    }
    for (int s = 0; s < static_cast<int>(segments_.size()); ++s) {
      Eigen::Vector3i lo, hi;
      range(segments_[s], lo, hi);
      for (int x = lo.x(); x <= hi.x(); ++x)
        for (int y = lo.y(); y <= hi.y(); ++y)
          for (int z = lo.z(); z <= hi.z(); ++z) {
            const long c = cell_of({x, y, z});
            if (pass == 1) cell_items_[cell_start_[c] + count[c]] = s;
            ++count[c];
          }
    }
  }
}

long TubeField::cell_of(const Eigen::Vector3i& c) const {
  return (long(c.z()) * dims_.y() + c.y()) * dims_.x() + c.x();
}

TubeField::Query TubeField::evaluate(const Eigen::Vector3d& p, bool blend) const {
  const Eigen::Vector3i c = ((p - origin_) / cell_).array().floor().cast<int>();
  if ((c.array() < 0).any() || (c.array() >= dims_.array()).any()) return {cell_, max_radius_};
  const long id = cell_of(c);
  const int begin = cell_start_[id], end = cell_start_[id + 1];
  if (begin == end) return {cell_, max_radius_};

  double f = INFINITY, fr = max_radius_;
  // Per-branch distances by zone; segments of a cell are listed branch by branch.
  int branch = -1;
  double d[3] = {INFINITY, INFINITY, INFINITY}, r[3] = {0, 0, 0};
  auto finish = [&]() {
    if (branch < 0) return;
    double value = d[0], radius = r[0];
    for (int z = 1; z <= 2; ++z) {
      if (!std::isfinite(d[z])) continue;
      const Plane& pl = z == 1 ? start_cap_[branch] : end_cap_[branch];
      const double clipped = std::max(d[z], pl.normal.dot(p - pl.center));
      if (clipped < value) {
        value = clipped;
        radius = r[z];
      }
    }
    if (!std::isfinite(f)) {
      f = value;
      fr = radius;
    } else {
      const double k = blend ? blend_ * std::min(fr, radius) : 0.0;
      if (value < f) fr = radius;
      f = smooth_min(f, value, k);
    }
  };
  for (int i = begin; i < end; ++i) {
    const Segment& s = segments_[cell_items_[i]];
    if (s.branch != branch) {
      finish();
      branch = s.branch;
      d[0] = d[1] = d[2] = INFINITY;
    }
    const Eigen::Vector3d ab = s.b - s.a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((p - s.a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    const double radius = s.ra + t * (s.rb - s.ra);
    const double dist = (p - s.a - t * ab).norm() - radius;
    if (dist < d[s.group]) {
      d[s.group] = dist;
      r[s.group] = radius;
    }
  }
  finish();
  return {f, fr};
}

double TubeField::value(const Eigen::Vector3d& p) const { return evaluate(p, true).value; }
double TubeField::hard_value(const Eigen::Vector3d& p) const { return evaluate(p, false).value; }
double TubeField::local_radius(const Eigen::Vector3d& p) const { return evaluate(p, false).radius; }

}  // namespace gw
