#include "task/branch_lumen.hpp"
#include "base/util/median.hpp"

#include <algorithm>
#include <stdexcept>

namespace gw {

RadiusProfile make_radius_profile(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& radii) {
  if (points.size() != radii.size() || points.empty())
    throw std::invalid_argument("radius profile: " + std::to_string(points.size()) + " points but " +
                                std::to_string(radii.size()) + " radii");
  RadiusProfile p;
  p.arc.reserve(points.size());
  p.radius = radii;
  double arc = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (i > 0) arc += (points[i] - points[i - 1]).norm();
    p.arc.push_back(arc);
  }
  return p;
}

double radius_at(const RadiusProfile& p, double arc) {
  if (arc <= p.arc.front()) return p.radius.front();
  if (arc >= p.arc.back()) return p.radius.back();
  const size_t i = static_cast<size_t>(std::upper_bound(p.arc.begin(), p.arc.end(), arc) - p.arc.begin());
  const double span = p.arc[i] - p.arc[i - 1];
  const double t = span > 0 ? (arc - p.arc[i - 1]) / span : 1.0;
  return p.radius[i - 1] + t * (p.radius[i] - p.radius[i - 1]);
}

BranchLumen make_branch_lumen(const std::vector<Eigen::Vector3d>& child_points, const std::vector<double>& child_radii,
                              const Polyline& course, const RadiusProfile& course_radius) {
  BranchLumen lumen;
  lumen.profile = make_radius_profile(child_points, child_radii);
  lumen.ostium_arc = lumen.profile.arc.back();
  double previous = 0.0;  // (distance to the course) - (course radius) at the previous point
  for (size_t i = 0; i < child_points.size(); ++i) {
    const PolylineProjection pc = project_onto_polyline(course, child_points[i]);
    const double outside = pc.distance - radius_at(course_radius, pc.arc);
    if (outside >= 0) {
      if (i == 0) {
        lumen.ostium_arc = 0.0;
      } else {
        const double t = previous < 0 ? -previous / (outside - previous) : 0.0;
        lumen.ostium_arc = lumen.profile.arc[i - 1] + t * (lumen.profile.arc[i] - lumen.profile.arc[i - 1]);
      }
      break;
    }
    previous = outside;
  }
  return lumen;
}

double median_radius(const RadiusProfile& p, double from, double to) {
  std::vector<double> r;
  for (double a = std::max(from, 0.0); a <= to; a += 1.0) r.push_back(radius_at(p, a));
  if (r.empty()) return radius_at(p, to);
  return median(r);
}

}  // namespace gw
