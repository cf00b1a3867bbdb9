#include "anatomy_gen/tree_geometry.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "anatomy_gen/catmull_rom.hpp"

namespace gw {
namespace {

std::string fmt(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(4);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

// Radius at spline parameter u: linear between control points.
double radius_at(const BranchSpec& b, double u) {
  const int n = static_cast<int>(b.radii.size());
  const int i = std::clamp(static_cast<int>(std::floor(u)), 0, n - 2);
  const double t = std::clamp(u - i, 0.0, 1.0);
  return (1.0 - t) * b.radii[i] + t * b.radii[i + 1];
}

// Closest point on segment ab to p, as the fraction along ab.
double segment_fraction(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = b - a;
  const double l2 = d.squaredNorm();
  return l2 > 0.0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
}

// Radius of the circle through three points (infinite when collinear).
double circumradius(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  const double area2 = (b - a).cross(c - a).norm();
  return area2 > 1e-15 ? ab * bc * ca / (2.0 * area2) : INFINITY;
}

// Where sample (branch, s) sits along the tree: each ancestor, the arclength on it and the
// distance travelled to get there. Tree distance between two samples goes through the
// closest common ancestor.
struct Climb {
  int branch;
  double s;
  double cost;
};

std::vector<Climb> climb(const std::vector<BranchCurve>& bs, int b, double s) {
  std::vector<Climb> out{{b, s, 0.0}};
  double cost = s;
  while (bs[b].parent >= 0) {
    const int p = bs[b].parent;
    out.push_back({p, bs[p].arclength[bs[b].parent_sample], cost});
    cost += out.back().s;
    b = p;
  }
  return out;
}

double tree_distance(const std::vector<BranchCurve>& bs, int a, double sa, int b, double sb) {
  const auto ca = climb(bs, a, sa), cb = climb(bs, b, sb);
  double best = INFINITY;
  for (const Climb& x : ca)
    for (const Climb& y : cb)
      if (x.branch == y.branch) best = std::min(best, x.cost + y.cost + std::abs(x.s - y.s));
  return best;
}

void check_bends(const BranchCurve& b) {
  for (size_t i = 1; i + 1 < b.points.size(); ++i) {
    // Skip the tiny steps around inserted attachment samples: curvature there is noise.
    if ((b.points[i] - b.points[i - 1]).norm() < 0.05 || (b.points[i + 1] - b.points[i]).norm() < 0.05) continue;
    const double R = circumradius(b.points[i - 1], b.points[i], b.points[i + 1]);
    if (R < b.radii[i])
      throw SpecError("branch '" + b.name + "' bends with a curvature radius of " + fmt(R) + " mm at " +
                      fmt(b.points[i]) + ", smaller than its radius " + fmt(b.radii[i]) +
                      " mm: the tube would fold onto itself");
  }
}

// Two parts of the tree closer than the sum of their radii, while much farther apart along
// the tree, overlap where no junction was meant. Near a junction, diverging branches are
// close in space and along the tree alike (chord ~ sin(angle/2) x tree distance), so the
// ratio test spares junctions with branching angles above ~17 degrees.
void check_intersections(const std::vector<BranchCurve>& bs) {
  struct Sample {
    int branch;
    int index;
  };
  std::vector<Sample> samples;
  for (int b = 0; b < static_cast<int>(bs.size()); ++b) {
    double last = -1e9;
    for (int i = 0; i < static_cast<int>(bs[b].points.size()); ++i)
      if (bs[b].arclength[i] - last >= 0.4 || i + 1 == static_cast<int>(bs[b].points.size())) {
        samples.push_back({b, i});
        last = bs[b].arclength[i];
      }
  }
  for (size_t i = 0; i < samples.size(); ++i)
    for (size_t j = i + 1; j < samples.size(); ++j) {
      const BranchCurve& A = bs[samples[i].branch];
      const BranchCurve& B = bs[samples[j].branch];
      const Eigen::Vector3d& pa = A.points[samples[i].index];
      const Eigen::Vector3d& pb = B.points[samples[j].index];
      const double reach = A.radii[samples[i].index] + B.radii[samples[j].index];
      const double chord = (pa - pb).norm();
      if (chord >= reach) continue;
      const double along = tree_distance(bs, samples[i].branch, A.arclength[samples[i].index], samples[j].branch,
                                         B.arclength[samples[j].index]);
      if (chord >= 0.15 * along) continue;
      const std::string who = samples[i].branch == samples[j].branch
                                  ? "branch '" + A.name + "' intersects itself"
                                  : "branches '" + A.name + "' and '" + B.name + "' intersect";
      throw SpecError(who + ": centreline points " + fmt(pa) + " and " + fmt(pb) + " are " + fmt(chord) +
                      " mm apart (closer than the sum of radii " + fmt(reach) + " mm) but " + fmt(along) +
                      " mm apart along the tree");
    }
}

std::vector<Eigen::Vector3d> sample_points(const BranchSpec& b, const std::vector<double>& us) {
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(us.size());
  for (double u : us) pts.push_back(catmull_rom_point(b.points, u));
  return pts;
}

// Stage 1: each child's first point (in `spec`) moved onto its parent's curve; returns each child's
// parent parameter (-1 for the root). Throws when a child starts off its parent.
std::vector<double> snap_children(TreeSpec& spec, double spacing) {
  const int n = static_cast<int>(spec.branches.size());
  std::vector<double> attach_u(n, -1.0);
  for (int b = 1; b < n; ++b) {
    BranchSpec& child = spec.branches[b];
    const BranchSpec& parent = spec.branches[child.parent];
    const CurveLocation loc = locate_on_branch(parent, child.points.front(), spacing);
    const double tol = std::max(0.02, 0.01 * parent.radii.front());
    if (loc.distance > tol)
      throw SpecError("branch '" + child.name + "' starts at " + fmt(child.points.front()) + ", " + fmt(loc.distance) +
                      " mm from the centreline of its parent '" + parent.name +
                      "': a child must start on its parent (within " + fmt(tol) + " mm)");
    attach_u[b] = loc.u;
    child.points.front() = catmull_rom_point(parent.points, loc.u);
    if ((child.points[1] - child.points[0]).norm() < 1e-6)
      throw SpecError("branch '" + child.name + "': its first two points coincide after snapping onto the parent");
  }
  return attach_u;
}

// Stage 2a: each branch's spline parameters to sample at, including its children's `attach_u`.
std::vector<std::vector<double>> sample_parameters(const TreeSpec& spec, const std::vector<double>& attach_u,
                                                   double spacing) {
  const int n = static_cast<int>(spec.branches.size());
  std::vector<std::vector<double>> us(n);
  for (int b = 0; b < n; ++b) us[b] = catmull_rom_parameters(spec.branches[b].points, spacing);
  for (int c = 1; c < n; ++c) {
    std::vector<double>& u = us[spec.branches[c].parent];
    const double a = attach_u[c];
    auto it = std::lower_bound(u.begin(), u.end(), a);
    // Reuse a sample that is already there, else insert one.
    if (it != u.end() && std::abs(*it - a) < 1e-9) continue;
    if (it != u.begin() && std::abs(*(it - 1) - a) < 1e-9) continue;
    u.insert(it, a);
  }
  return us;
}

// Stage 2b: g.branches from the spec sampled at `us`: names, parents, points, radii, arclengths.
void sample_branches(const TreeSpec& spec, const std::vector<std::vector<double>>& us, TreeGeometry& g) {
  const int n = static_cast<int>(spec.branches.size());
  g.branches.resize(n);
  for (int b = 0; b < n; ++b) {
    const BranchSpec& s = spec.branches[b];
    BranchCurve& c = g.branches[b];
    c.name = s.name;
    c.parent = s.parent;
    c.points = sample_points(s, us[b]);
    for (double u : us[b]) c.radii.push_back(radius_at(s, u));
    c.arclength.assign(c.points.size(), 0.0);
    for (size_t i = 1; i < c.points.size(); ++i)
      c.arclength[i] = c.arclength[i - 1] + (c.points[i] - c.points[i - 1]).norm();
  }
}

// Stage 2c: each child's parent_sample (its `attach_u` among the parent's `us`), added to the parent's
// child_samples. Throws for a child at its parent's first point.
void link_children(const std::vector<double>& attach_u, const std::vector<std::vector<double>>& us, TreeGeometry& g) {
  const int n = static_cast<int>(g.branches.size());
  for (int b = 1; b < n; ++b) {
    BranchCurve& c = g.branches[b];
    BranchCurve& p = g.branches[c.parent];
    const std::vector<double>& u = us[c.parent];
    c.parent_sample = static_cast<int>(std::lower_bound(u.begin(), u.end(), attach_u[b] - 1e-9) - u.begin());
    if (c.parent_sample == 0 || p.arclength[c.parent_sample] < 1e-3)
      throw SpecError("branch '" + c.name + "' starts at the first point of its parent '" + p.name +
                      "': attach it to an earlier branch, or further along the parent");
    p.child_samples.push_back(c.parent_sample);
  }
}

// Stage 2d: child_samples sorted and unique, and which ends are capped (the root's start; an end
// where no children start). Throws for an end where a single child starts.
void mark_caps(TreeGeometry& g) {
  const int n = static_cast<int>(g.branches.size());
  for (int b = 0; b < n; ++b) {
    BranchCurve& c = g.branches[b];
    std::sort(c.child_samples.begin(), c.child_samples.end());
    c.child_samples.erase(std::unique(c.child_samples.begin(), c.child_samples.end()), c.child_samples.end());
    const int last = static_cast<int>(c.points.size()) - 1;
    const bool children_at_end = !c.child_samples.empty() && c.child_samples.back() == last;
    if (children_at_end) {
      int count = 0;
      for (int k = 1; k < n; ++k) count += (g.branches[k].parent == b && g.branches[k].parent_sample == last);
      if (count < 2)
        throw SpecError("branch '" + c.name + "' ends where a single child starts: merge them into one branch");
    }
    c.cap_start = (b == 0);
    c.cap_end = !children_at_end;
  }
}

// Stage 4: g's radius range, the tubes' bounding box, and its caps (inlet first, then outlets).
void measure_extent(TreeGeometry& g) {
  const int n = static_cast<int>(g.branches.size());
  g.min_radius = INFINITY;
  g.max_radius = 0.0;
  g.bbox_min = Eigen::Vector3d::Constant(INFINITY);
  g.bbox_max = Eigen::Vector3d::Constant(-INFINITY);
  for (int b = 0; b < n; ++b) {
    const BranchCurve& c = g.branches[b];
    for (size_t i = 0; i < c.points.size(); ++i) {
      g.min_radius = std::min(g.min_radius, c.radii[i]);
      g.max_radius = std::max(g.max_radius, c.radii[i]);
      g.bbox_min = g.bbox_min.cwiseMin(c.points[i] - Eigen::Vector3d::Constant(c.radii[i]));
      g.bbox_max = g.bbox_max.cwiseMax(c.points[i] + Eigen::Vector3d::Constant(c.radii[i]));
    }
    if (c.cap_start)
      g.caps.push_back({c.points.front(), (c.points[0] - c.points[1]).normalized(), c.radii.front(), b, true});
  }
  for (int b = 0; b < n; ++b) {
    const BranchCurve& c = g.branches[b];
    const size_t m = c.points.size();
    if (c.cap_end) g.caps.push_back({c.points.back(), (c.points[m - 1] - c.points[m - 2]).normalized(), c.radii.back(), b, false});
  }
}

}  // namespace

CurveLocation locate_on_branch(const BranchSpec& parent, const Eigen::Vector3d& p, double spacing) {
  const std::vector<double> us = catmull_rom_parameters(parent.points, spacing);
  const std::vector<Eigen::Vector3d> pts = sample_points(parent, us);
  CurveLocation best{0.0, INFINITY};
  for (size_t i = 0; i + 1 < pts.size(); ++i) {
    const double t = segment_fraction(pts[i], pts[i + 1], p);
    const double d = (pts[i] + t * (pts[i + 1] - pts[i]) - p).norm();
    if (d < best.distance) best = {us[i] + t * (us[i + 1] - us[i]), d};
  }
  // Control points are exact samples: snap rounding noise onto them.
  if (std::abs(best.u - std::round(best.u)) < 1e-6) best.u = std::round(best.u);
  return best;
}

TreeGeometry build_tree_geometry(const TreeSpec& spec_in, double spacing) {
  TreeSpec spec = spec_in;
  // 1. Snap every child's first point onto its parent (parents come first, so they are final).
  const std::vector<double> attach_u = snap_children(spec, spacing);
  // 2. Sample each branch, with its children's start parameters as exact samples.
  TreeGeometry g;
  g.blend = spec.blend;
  g.edge_per_radius = spec.edge_per_radius;
  const std::vector<std::vector<double>> us = sample_parameters(spec, attach_u, spacing);
  sample_branches(spec, us, g);
  link_children(attach_u, us, g);
  mark_caps(g);
  // 3. Shape checks.
  for (const BranchCurve& c : g.branches) check_bends(c);
  check_intersections(g.branches);
  // 4. Caps, radius range, bounding box.
  measure_extent(g);
  return g;
}

}  // namespace gw
