#include "centerline/junction_centre.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "centerline/merged_lumen_axis.hpp"
#include "centerline/polyline_tools.hpp"
#include "base/graph/centerline_graph.hpp"

namespace gw {
namespace {

// A side branch is recognised by its arms' directions (the two others nearly opposite, cos < -0.8)
// or, off a curving vessel, by its radius: below this share of both others' while their cos < -0.5.
constexpr double kSideRadiusShare = 0.8;
constexpr double kCurvedParentCos = 0.0;
// A clean tube found further out than this many radii is no guide to the axis at the junction
// (the branch curves in between): the fixed window near the junction is used instead.
constexpr double kCleanReach = 8.0;
// Junctions closer than this many of the widest radius along the arm between them are two origins
// on one wide vessel.
constexpr double kCloseJunctions = 2.0;
// A terminal arm shorter than this many of its widest radius is a skeleton spur (SkeletonCleanup's
// spur_factor default).
constexpr double kStubFactor = 2.0;

// A branch seen from the junction: its points and radii running away from it.
struct Arm {
  size_t chain = 0;
  bool reversed = false;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> radii;
  std::vector<double> elongation;
};

Arm arm_of(const RefinedBranch& b, size_t chain, bool reversed) {
  Arm a{chain, reversed, b.points, b.radii, b.elongation};
  a.elongation.resize(a.points.size(), std::numeric_limits<double>::infinity());
  if (reversed) {
    std::reverse(a.points.begin(), a.points.end());
    std::reverse(a.radii.begin(), a.radii.end());
    std::reverse(a.elongation.begin(), a.elongation.end());
  }
  return a;
}

// Arc length from the junction to where the arm becomes a clean round tube (three
// sections in a row with elongation < 1.12, at least half a radius out): the vessels
// of a shallow-angle bifurcation share one lumen for several radii, and lines fitted
// inside it would follow the merged lumen, not either axis. -1 when there is none in
// the first 60% of the arm and within kCleanReach radii.
double clean_start(const Arm& a, const std::vector<double>& s, double r) {
  constexpr double kClean = 1.12;
  for (size_t i = 0; i + 2 < a.points.size() && s[i] <= 0.6 * s.back() && s[i] <= kCleanReach * r; ++i) {
    if (s[i] < 0.5 * r) continue;
    if (a.elongation[i] < kClean && a.elongation[i + 1] < kClean && a.elongation[i + 2] < kClean) return s[i];
  }
  return -1.0;
}

// One junction while it is re-centred: its arms, each arm's fitted axis, the centre, and what each
// arm is re-attached with. The stages below fill it in order.
struct JunctionFit {
  std::vector<Arm> arms;
  // per arm: arc length dropped from the junction end, the axis (a point `mid`, unit `dir` away from
  // the junction, the window's first point `start`), its radius, whether it leads to a junction close by
  std::vector<double> cut, radius;
  std::vector<Eigen::Vector3d> start, dir, mid;
  std::vector<char> between_close;
  double widest = 0.0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();  // sum of the axes' normal projectors (least squares)
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  bool placed = false;
  bool side_case = false;
  size_t side_arm = 0;
  // per arm: the run from the centre to its window (lead, excluding both) with measured radii when it
  // was traced, and the centres recovered inside the merged lumen (merged_lumen_axis.hpp)
  std::vector<std::vector<Eigen::Vector3d>> lead, traced_centres;
  std::vector<std::vector<double>> lead_radii, traced_radii;
};

// Stage 1. The chains meeting at junction `v`, as arms running away from it; a terminal stub (a
// skeleton spur that survived pruning, shorter than kStubFactor of its widest radius; the graph walk
// drops it too, extract_centerline.cpp) has no axis to fit: without it a junction with three real
// arms is still re-centred.
std::vector<Arm> junction_arms(const SkeletonTree& tree, const std::vector<RefinedBranch>& branches,
                               const std::vector<int>& degree, size_t v) {
  std::vector<Arm> arms;
  for (size_t i = 0; i < tree.chains.size(); ++i) {
    if (tree.chains[i].a == static_cast<int>(v)) arms.push_back(arm_of(branches[i], i, false));
    if (tree.chains[i].b == static_cast<int>(v) && tree.chains[i].a != static_cast<int>(v))
      arms.push_back(arm_of(branches[i], i, true));
  }
  if (arms.size() >= 4) {
    std::vector<Arm> real;
    for (const Arm& a : arms) {
      const SkeletonChain& c = tree.chains[a.chain];
      const int far = a.reversed ? c.a : c.b;
      const bool stub = degree[far] == 1 && !tree.at_known_end(a.points.back()) &&
                        polyline_length(a.points) < kStubFactor * *std::max_element(a.radii.begin(), a.radii.end());
      if (!stub) real.push_back(a);
    }
    if (real.size() >= 3) arms = std::move(real);
  }
  return arms;
}

// Stage 2. One line per arm, fitted over about two radii where the arm becomes a clean tube (or over
// [1.5 r, 3.5 r] when it never does); false when an arm is too short for a window.
bool fit_arm_axes(const SkeletonTree& tree, const std::vector<int>& degree, size_t v, JunctionFit& f) {
  const size_t n = f.arms.size();
  f.cut.assign(n, 0.0);
  f.start.assign(n, Eigen::Vector3d::Zero());
  f.dir.assign(n, Eigen::Vector3d::Zero());
  f.mid.assign(n, Eigen::Vector3d::Zero());
  f.radius.assign(n, 0.0);
  f.between_close.assign(n, 0);
  for (size_t k = 0; k < n; ++k) {
    const auto& p = f.arms[k].points;
    std::vector<double> s(p.size(), 0.0);
    for (size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
    std::vector<double> near(f.arms[k].radii.begin(),
                             f.arms[k].radii.begin() + std::min<long>(static_cast<long>(p.size()), 16));
    std::sort(near.begin(), near.end());
    const double r = near[near.size() / 2];
    f.widest = std::max(f.widest, r);
    f.radius[k] = r;
    // A short piece of a wide vessel between this junction and the next (closer than
    // kCloseJunctions of its widest radius): both junction nodes sit off that vessel's axis on
    // the side the branches leave, so the chain dips between them and a line fitted to part of
    // it is tilted; the direction from junction to junction is the vessel's.
    const SkeletonChain& c = tree.chains[f.arms[k].chain];
    const int other = f.arms[k].reversed ? c.a : c.b;
    const Eigen::Vector3d to_other = tree.nodes[other] - tree.nodes[v];
    const double widest_along = *std::max_element(f.arms[k].radii.begin(), f.arms[k].radii.end());
    f.between_close[k] =
        other != static_cast<int>(v) && degree[other] >= 3 && to_other.norm() < kCloseJunctions * widest_along;
    double s0 = clean_start(f.arms[k], s, r), s1 = s0 + 4.0 * r;
    if (s0 < 0) s0 = std::min(1.5 * r, 0.3 * s.back()), s1 = std::min(3.5 * r, 0.6 * s.back());
    s1 = std::min(s1, 0.8 * s.back());
    f.cut[k] = s0;
    std::vector<Eigen::Vector3d> window;
    for (size_t i = 0; i < p.size(); ++i)
      if (s[i] >= s0 && s[i] <= s1) window.push_back(p[i]);
    if (window.size() < 2 || !(r > 0)) return false;
    Eigen::Vector3d mean, d;
    fit_line(window, mean, d);  // d points away from the junction
    if (f.between_close[k]) d = to_other.normalized();
    f.dir[k] = d;
    f.mid[k] = mean;
    f.start[k] = window.front();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
    f.A += P;
    f.rhs += P * mean;
  }
  return true;
}

// Stage 3. The least-squares point of all axes, trusted only when they are not nearly parallel (a
// shallow side branch makes this ill-conditioned; stage 4 handles it); else the skeleton's node.
void least_squares_centre(const Eigen::Vector3d& node, JunctionFit& f) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> check(f.A);
  f.placed = check.eigenvalues().minCoeff() >= 0.05 * check.eigenvalues().maxCoeff();
  f.centre = f.placed ? Eigen::Vector3d(f.A.ldlt().solve(f.rhs)) : node;
}

// Stage 4a. The two arms of the vessel that goes on past a side branch, into bi and bj: the pair most
// nearly opposite, or the two others of a much thinner arm; false when the junction is no side branch.
bool parent_arms(const JunctionFit& f, size_t& bi, size_t& bj) {
  const auto& dir = f.dir;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = i + 1; j < 3; ++j)
      if (dir[i].dot(dir[j]) < dir[bi].dot(dir[bj])) bi = i, bj = j;
  // A much thinner arm is the side branch even where the vessel it leaves curves through the
  // junction (an aortic arch, a bending trunk): its two arms are then less than opposite.
  // An arm to a junction close by is the wide vessel itself (its chain hugs the wall between
  // the two origins, so its measured radius says nothing): never the side branch.
  auto side_radius = [&](size_t k) {
    return f.between_close[k] ? std::numeric_limits<double>::infinity() : f.radius[k];
  };
  size_t thin = 0;
  for (size_t k = 1; k < 3; ++k)
    if (side_radius(k) < side_radius(thin)) thin = k;
  const size_t ti = thin == 0 ? 1 : 0, tj = thin == 2 ? 1 : 2;
  const bool thin_side = side_radius(thin) < kSideRadiusShare * std::min(side_radius(ti), side_radius(tj)) &&
                         dir[ti].dot(dir[tj]) < kCurvedParentCos;
  if (thin_side) bi = ti, bj = tj;
  return thin_side || dir[bi].dot(dir[bj]) < -0.8;
}

// The parent's axis: a cubic Hermite curve from arm bi's window start (u = 0) to arm bj's (u = 1),
// the windows' lines beyond; `samples` is it at u = -0.5 .. 1.5 in steps of 1/200.
struct ParentAxis {
  const std::vector<Eigen::Vector3d>& dir;
  size_t bi, bj;
  Eigen::Vector3d P0, P1;
  double L;
  Eigen::Vector3d T0, T1;
  std::vector<Eigen::Vector3d> samples;

  ParentAxis(const JunctionFit& f, size_t i, size_t j)
      : dir(f.dir), bi(i), bj(j), P0(f.start[bi]), P1(f.start[bj]), L((P1 - P0).norm()), T0(-dir[bi] * L),
        T1(dir[bj] * L) {
    for (int k = -100; k <= 300; ++k) samples.push_back(point(k / 200.0));
  }
  Eigen::Vector3d hermite(double u) const {
    const double u2 = u * u, u3 = u2 * u;
    return ((2 * u3 - 3 * u2 + 1) * P0 + (u3 - 2 * u2 + u) * T0 + (-2 * u3 + 3 * u2) * P1 + (u3 - u2) * T1).eval();
  }
  Eigen::Vector3d point(double u) const {
    return u < 0 ? (P0 - dir[bi] * (u * L)).eval() : u > 1 ? (P1 + dir[bj] * ((u - 1) * L)).eval() : hermite(u);
  }
  // Distance from q to the sampled axis.
  double distance(const Eigen::Vector3d& q) const {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i + 1 < samples.size(); ++i) {
      const Eigen::Vector3d a = samples[i], ab = samples[i + 1] - a;
      const double t = std::clamp((q - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
      best = std::min(best, (q - a - t * ab).norm());
    }
    return best;
  }
};

// Stage 4b. The side branch's axis near the junction, from its own wall inside the merged lumen
// (merged_lumen_axis.hpp), into f's mid, dir and traced arrays; the clean-tube line stays when that fails.
void trace_side_arm(const VesselWall& wall, double spacing, double wall_noise, const ParentAxis& parent,
                    size_t side, JunctionFit& f) {
  const double parent_r = 0.5 * (f.radius[parent.bi] + f.radius[parent.bj]);
  const MergedLumenQuery query{
      [&](const Eigen::Vector3d& q) { return parent.distance(q) > parent_r + 0.5 * f.radius[side]; },
      [&](const Eigen::Vector3d& q) { return parent.distance(q) < 0.25 * parent_r; }};
  const MergedLumenAxis traced =
      trace_merged_lumen_axis(wall, f.mid[side], f.dir[side], f.radius[side], query, spacing, 25.0, wall_noise);
  if (traced.ok) {
    f.mid[side] = traced.point;
    f.dir[side] = traced.direction;
    f.traced_centres[side] = traced.centres;
    f.traced_radii[side] = traced.radii;
  }
}

// Stage 4c. The parameter `best` where the parent's axis passes nearest to the side arm's axis, and
// that distance `best_gap`.
void nearest_on_parent(const ParentAxis& parent, const JunctionFit& f, size_t side, double& best, double& best_gap) {
  auto gap = [&](double u) {
    const Eigen::Vector3d q = parent.point(u) - f.mid[side];
    return (q - q.dot(f.dir[side]) * f.dir[side]).norm();
  };
  // The centre may lie a little inside either parent window (a shallow branch's merged lumen
  // can push the proximal window's clean start right up to the true junction).
  best = 0.0, best_gap = gap(0.0);
  for (int i = -100; i <= 300; ++i)
    if (gap(i / 200.0) < best_gap) best_gap = gap(i / 200.0), best = i / 200.0;
  for (double h = 1.0 / 200; h > 1e-6; h *= 0.5)
    for (double u : {best - h, best + h})
      if (u >= -0.5 && u <= 1.5 && gap(u) < best_gap) best_gap = gap(u), best = u;
}

// Stage 4d. The centre at `best` on the parent's axis, with lead-ins along that axis to both windows
// (f.lead) and a cut past the centre for a window it fell into.
void place_on_parent(const ParentAxis& parent, double best, double spacing, JunctionFit& f) {
  const size_t bi = parent.bi, bj = parent.bj;
  const double L = parent.L;
  f.centre = parent.point(best);
  f.placed = true;
  const int n = std::max(2, static_cast<int>(std::round(L / spacing)));
  // Lead-ins along the parent axis to each window start (excluded), skipping the part of a
  // window the centre fell into: that arm is then cut past the centre.
  for (int i = static_cast<int>(std::floor(best * n)); i > 0; --i) f.lead[bi].push_back(parent.point(double(i) / n));
  for (int i = static_cast<int>(std::ceil(best * n)); i < n; ++i) f.lead[bj].push_back(parent.point(double(i) / n));
  if (best > 1.0) f.cut[bj] += (best - 1.0) * L + spacing;
  if (best < 0.0) f.cut[bi] += -best * L + spacing;
  // lead[] excludes the centre and the window start themselves.
  if (!f.lead[bi].empty() && (f.lead[bi].front() - f.centre).norm() < 0.25 * spacing) f.lead[bi].erase(f.lead[bi].begin());
  if (!f.lead[bj].empty() && (f.lead[bj].front() - f.centre).norm() < 0.25 * spacing) f.lead[bj].erase(f.lead[bj].begin());
}

// Stage 4. Side branch off a vessel that goes on (two arms nearly opposite): the true centre is on
// that vessel's axis, which curves between its two windows. Follow it as a cubic Hermite curve
// between the windows and put the centre where it passes nearest to the side branch's axis. (The
// plain least-squares point sits off a curved axis by its sagitta, and at shallow side-branch
// angles that error is multiplied along it.)
void side_branch_centre(const VesselWall& wall, double spacing, double wall_noise, JunctionFit& f) {
  if (f.arms.size() != 3) return;
  size_t bi = 0, bj = 1;
  if (!parent_arms(f, bi, bj)) return;
  const size_t side = 3 - bi - bj;
  const ParentAxis parent(f, bi, bj);
  trace_side_arm(wall, spacing, wall_noise, parent, side, f);
  f.side_case = true;
  f.side_arm = side;
  double best = 0.0, best_gap = 0.0;
  nearest_on_parent(parent, f, side, best, best_gap);
  if (!(best > -0.5 && best < 1.5 && best_gap < 1.5 * f.widest)) return;
  place_on_parent(parent, best, spacing, f);
}

// Stage 5. Every other arm is traced back to the centre through the merged lumen too: its own wall is
// what lies outside the other arms' tubes (taken as half-lines from the centre). The two arms of a
// vessel that goes on past a side branch are one tube: they do not mask each other. A traced arm then
// runs from the centre (straight) to its nearest recovered centre, through the recovered centres, then
// on along its old points beyond them.
void trace_arms(const VesselWall& wall, double spacing, double wall_noise, JunctionFit& f) {
  const auto& arms = f.arms;
  const Eigen::Vector3d centre = f.centre;
  for (size_t k = 0; k < arms.size(); ++k) {
    if (!f.traced_centres[k].empty()) continue;
    std::vector<size_t> others;
    for (size_t j = 0; j < arms.size(); ++j)
      if (j != k && !(f.side_case && k != f.side_arm && j != f.side_arm)) others.push_back(j);
    const MergedLumenQuery query{
        [&](const Eigen::Vector3d& q) {
          for (size_t j : others) {
            const double t = std::max(0.0, (q - centre).dot(f.dir[j]));
            if ((q - centre - t * f.dir[j]).norm() <= f.radius[j] + 0.5 * std::min(f.radius[j], f.radius[k])) return false;
          }
          return true;
        },
        [&](const Eigen::Vector3d& q) { return (q - centre).dot(f.dir[k]) < 0.5 * f.radius[k]; }};
    const MergedLumenAxis traced =
        trace_merged_lumen_axis(wall, f.mid[k], f.dir[k], f.radius[k], query, spacing, 25.0, wall_noise);
    if (traced.ok) f.traced_centres[k] = traced.centres, f.traced_radii[k] = traced.radii;
  }
  for (size_t k = 0; k < arms.size(); ++k) {
    if (f.traced_centres[k].empty()) continue;
    const Arm& a = arms[k];
    const std::vector<Eigen::Vector3d>& found = f.traced_centres[k];
    const Eigen::Vector3d d = f.dir[k];
    auto along = [&](const Eigen::Vector3d& q) { return (q - centre).dot(d); };
    std::vector<Eigen::Vector3d> run;
    std::vector<double> run_radii;
    const int steps = std::max(1, static_cast<int>(std::round(along(found.front()) / spacing)));
    for (int j = 1; j < steps; ++j) {
      run.push_back(centre + (found.front() - centre) * (double(j) / steps));
      run_radii.push_back(f.traced_radii[k].front());
    }
    for (size_t i = 0; i < found.size(); ++i)
      if (along(found[i]) > (run.empty() ? 0.0 : along(run.back())) + 0.5 * spacing) {
        run.push_back(found[i]);
        run_radii.push_back(f.traced_radii[k][i]);
      }
    if (run.empty()) continue;
    size_t first = 0;
    double s = 0.0;
    while (first + 1 < a.points.size() && along(a.points[first]) < along(run.back()) + 0.5 * spacing) {
      s += (a.points[first + 1] - a.points[first]).norm();
      ++first;
    }
    f.cut[k] = s;
    f.lead[k] = std::move(run);
    f.lead_radii[k] = std::move(run_radii);
  }
}

// Stage 6. Re-attach: drop each arm's first `cut` of length and run from the centre to what is left,
// along its lead (traced or along the parent's axis) or straight.
void reattach_arms(const JunctionFit& f, double spacing, std::vector<RefinedBranch>& branches) {
  for (size_t k = 0; k < f.arms.size(); ++k) {
    const Arm& a = f.arms[k];
    size_t first = 0;
    double s = 0.0;
    while (first + 1 < a.points.size() && s < f.cut[k]) {
      s += (a.points[first + 1] - a.points[first]).norm();
      ++first;
    }
    std::vector<Eigen::Vector3d> pts{f.centre};
    std::vector<double> rad{f.lead_radii[k].empty() ? a.radii[first] : f.lead_radii[k].front()};
    std::vector<double> elong{std::numeric_limits<double>::infinity()};
    const Eigen::Vector3d target = a.points[first];
    if (!f.lead[k].empty()) {
      for (size_t i = 0; i < f.lead[k].size(); ++i) {
        pts.push_back(f.lead[k][i]);
        rad.push_back(f.lead_radii[k].empty() ? a.radii[first] : f.lead_radii[k][i]);
        elong.push_back(std::numeric_limits<double>::infinity());
      }
    } else {
      const int steps = std::max(1, static_cast<int>(std::round((target - f.centre).norm() / spacing)));
      for (int j = 1; j < steps; ++j) {
        pts.push_back(f.centre + (target - f.centre) * (double(j) / steps));
        rad.push_back(a.radii[first]);
        elong.push_back(std::numeric_limits<double>::infinity());
      }
    }
    pts.insert(pts.end(), a.points.begin() + static_cast<long>(first), a.points.end());
    rad.insert(rad.end(), a.radii.begin() + static_cast<long>(first), a.radii.end());
    elong.insert(elong.end(), a.elongation.begin() + static_cast<long>(first), a.elongation.end());
    if (a.reversed) {
      std::reverse(pts.begin(), pts.end());
      std::reverse(rad.begin(), rad.end());
      std::reverse(elong.begin(), elong.end());
    }
    branches[a.chain].elongation = std::move(elong);
    branches[a.chain].points = std::move(pts);
    branches[a.chain].radii = std::move(rad);
  }
}

}  // namespace

void recentre_junctions(const SkeletonTree& tree, std::vector<Eigen::Vector3d>& nodes,
                        std::vector<RefinedBranch>& branches, const VesselWall& wall, double spacing,
                        double max_shift, double wall_noise) {
  const std::vector<int> degree = tree.degree();
  for (size_t v = 0; v < tree.nodes.size(); ++v) {
    if (degree[v] < 3) continue;
    JunctionFit f;
    f.arms = junction_arms(tree, branches, degree, v);
    f.lead.resize(f.arms.size());
    f.lead_radii.resize(f.arms.size());
    f.traced_centres.resize(f.arms.size());
    f.traced_radii.resize(f.arms.size());
    if (!fit_arm_axes(tree, degree, v, f)) continue;
    least_squares_centre(nodes[v], f);
    side_branch_centre(wall, spacing, wall_noise, f);
    if (!f.placed || !f.centre.allFinite() || (f.centre - nodes[v]).norm() > max_shift * f.widest) continue;
    nodes[v] = f.centre;
    trace_arms(wall, spacing, wall_noise, f);
    reattach_arms(f, spacing, branches);
  }
}

}  // namespace gw
