#include "centerline/refine_branch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "centerline/cross_section.hpp"
#include "centerline/open_cross_section.hpp"
#include "centerline/polyline_tools.hpp"
#include "base/graph/centerline_graph.hpp"

namespace gw {
namespace {

// A section that is no clean tube is re-centred on the circle of the wall around an opening
// (open_cross_section.hpp) only on a chain between two junctions less than that circle's diameter
// apart (a piece of a wider vessel between two branch origins, as on an aortic arch, not a vessel
// of its own), and only when that circle's radius is at least kOffAxisRatio times the
// point's distance to the wall and its centre at least half a radius to the side: the skeleton
// is then grossly off-axis, whereas the merged lumen of an ordinary fork puts it about one child
// radius from the wall, and a point near a cap is on the axis; those stay as they are. Rays reach
// kOpenReach wall distances (across the wider vessel from a point near its wall).
constexpr double kOffAxisRatio = 2.0;
constexpr double kOpenReach = 20.0;

// Per point: fitted radius where the cross-section is a tube, else NaN.
// `open_below`: sections are also fitted around an opening (above) where that circle's radius
// exceeds this (0: never).
std::vector<double> tube_radii(const std::vector<Eigen::Vector3d>& p, const VesselWall& wall, int rays,
                               std::vector<Eigen::Vector3d>* centres, std::vector<double>* elongation = nullptr,
                               double open_below = 0.0, double wall_noise = 0.0) {
  const auto tangent = polyline_tangents(smooth_polyline(p, 4));
  std::vector<double> r(p.size(), std::nan(""));
  if (centres) *centres = p;
  if (elongation) elongation->assign(p.size(), std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < p.size(); ++i) {
    const double near = wall.distance(p[i]);
    CrossSection cs = fit_cross_section(wall, p[i], tangent[i], 4.0 * near + 1e-9, rays, wall_noise);
    if (!cs.tube) {
      if (!(open_below > 0)) continue;
      // A point far off the axis of a much wider vessel (the skeleton between two branch origins
      // on an aortic arch runs along the arch's roof): the wall around the openings is one circle.
      const CrossSection open = fit_open_cross_section(wall, p[i], tangent[i], kOpenReach * near + 1e-9);
      if (!open.tube || open.radius <= open_below || open.radius < kOffAxisRatio * near ||
          (open.centre - p[i]).norm() < 0.5 * open.radius)
        continue;
      cs = open;
    }
    if (elongation) (*elongation)[i] = cs.elongation;
    r[i] = cs.radius;
    if (centres) (*centres)[i] = cs.centre;
  }
  return r;
}

// Replaces the tail after the last tube section by a straight run to the wall along the
// branch direction there. Returns false (nothing changed) when no section is a tube.
bool extend_end_to_wall(std::vector<Eigen::Vector3d>& p, const std::vector<double>& radius, const VesselWall& wall,
                        double spacing) {
  int last = -1;
  for (int i = static_cast<int>(p.size()) - 1; i >= 0; --i)
    if (!std::isnan(radius[i])) {
      last = i;
      break;
    }
  if (last < 1) return false;
  // Direction over about one radius of centred points before `last`.
  int back = last;
  double run = 0.0;
  while (back > 0 && run < radius[last] && !std::isnan(radius[back - 1])) {
    run += (p[back] - p[back - 1]).norm();
    --back;
  }
  if (back == last) back = last - 1;
  const Eigen::Vector3d dir = (p[last] - p[back]).normalized();
  const double reach = wall.ray_hit(p[last], dir);
  // Never run further than six radii: a ray escaping down a long lumen means the
  // skeleton already reached the end (a rounded tip) or the direction is off.
  const double limit = std::max(6.0 * radius[last], 2.0 * (p.back() - p[last]).norm());
  if (!(reach < limit)) return false;
  p.resize(static_cast<size_t>(last) + 1);
  const int steps = std::max(1, static_cast<int>(std::ceil(reach / spacing)));
  for (int k = 1; k <= steps; ++k) p.push_back(p[last] + dir * (reach * k / steps));
  return true;
}

}  // namespace

RefinedBranch refine_branch(const std::vector<Eigen::Vector3d>& chain, bool free_start, bool free_end,
                            const VesselWall& wall, const BranchRefinement& o) {
  RefinedBranch out;
  std::vector<Eigen::Vector3d> p = smooth_polyline(resample_polyline(chain, o.spacing), 2);
  std::vector<double> r(p.size(), std::nan(""));
  // extend_end_to_wall keeps points 0..last, so `r` stays aligned after padding.
  auto extend_free_ends = [&] {
    if (free_end) {
      extend_end_to_wall(p, r, wall, o.spacing);
      r.resize(p.size(), std::nan(""));
    }
    if (free_start) {
      std::reverse(p.begin(), p.end());
      std::reverse(r.begin(), r.end());
      extend_end_to_wall(p, r, wall, o.spacing);
      r.resize(p.size(), std::nan(""));
      std::reverse(p.begin(), p.end());
      std::reverse(r.begin(), r.end());
    }
  };
  // Re-centre, extend the free ends along the first estimate (the skeleton stops short
  // of an outlet, where the axis may still curve), re-centre the extension too, and
  // finally run the last straight piece from the last clean section to the wall.
  const int passes = std::max(1, o.recentre_passes);
  double length = 0.0;
  for (size_t i = 1; i < p.size(); ++i) length += (p[i] - p[i - 1]).norm();
  const double open_below = free_start || free_end ? 0.0 : 0.5 * length;
  for (int pass = 0; pass < passes + 1; ++pass) {
    std::vector<Eigen::Vector3d> centred;
    r = tube_radii(p, wall, o.rays, &centred, nullptr, open_below, o.wall_noise);
    for (size_t i = 1; i + 1 < p.size(); ++i) p[i] = centred[i];
    if (free_start) p.front() = centred.front();
    if (free_end) p.back() = centred.back();
    if (pass == 0) extend_free_ends();
  }
  extend_free_ends();
  p = resample_polyline(taubin_smooth_polyline(p, o.smoothing_iterations), o.spacing);
  r = tube_radii(p, wall, o.rays, nullptr, &out.elongation, 0.0, o.wall_noise);
  // Fill non-tube sections (bifurcations, caps) by interpolating along the branch
  // between tube sections; a branch with no tube section keeps the wall distance.
  std::vector<double> s(p.size(), 0.0);
  for (size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
  std::vector<size_t> known;
  for (size_t i = 0; i < p.size(); ++i)
    if (!std::isnan(r[i])) known.push_back(i);
  out.radii.resize(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    if (!std::isnan(r[i])) {
      out.radii[i] = r[i];
      continue;
    }
    if (known.empty()) {
      out.radii[i] = wall.distance(p[i]);
      continue;
    }
    const auto next = std::lower_bound(known.begin(), known.end(), i);
    if (next == known.begin()) out.radii[i] = r[*next];
    else if (next == known.end()) out.radii[i] = r[known.back()];
    else {
      const size_t a = *(next - 1), b = *next;
      const double t = (s[i] - s[a]) / std::max(s[b] - s[a], 1e-12);
      out.radii[i] = (1 - t) * r[a] + t * r[b];
    }
  }
  out.points = std::move(p);
  return out;
}

}  // namespace gw
