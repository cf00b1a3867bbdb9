#include "base/graph/nearest_target.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace gw {
namespace {

std::string xyz(const Eigen::Vector3d& p) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return s;
}

}  // namespace

int nearest_target(const CenterlineGraph& g, const Eigen::Vector3d& point) {
  if (!point.allFinite()) throw std::invalid_argument("target point " + xyz(point) + " is not finite");
  if (g.targets.empty()) throw std::invalid_argument("the centerline has no target to pick from");
  const Terminal* best = nullptr;
  for (const Terminal& t : g.targets)
    if (!best || (t.position - point).norm() < (best->position - point).norm()) best = &t;
  const double d = (best->position - point).norm();
  std::string list;
  for (const Terminal& t : g.targets) list += (list.empty() ? "" : ", ") + std::to_string(t.id) + " " + xyz(t.position);
  char text[256];
  if ((g.inlet.position - point).norm() < d) {
    std::snprintf(text, sizeof text, "target point %s is nearer the inlet %s (%.2f mm) than any target (target %d: %.2f mm)",
                  xyz(point).c_str(), xyz(g.inlet.position).c_str(), (g.inlet.position - point).norm(), best->id, d);
    throw std::invalid_argument(std::string(text) + "; targets: " + list);
  }
  const double limit = std::max(kTargetPointRadii * best->radius, kTargetPointMinMm);
  if (d > limit) {
    std::snprintf(text, sizeof text,
                  "target point %s is %.2f mm from the nearest target end (target %d), more than %.2f mm "
                  "(%.0f radii, at least %.0f mm): a point in another frame (LPS vs RAS?) or not at a vessel end",
                  xyz(point).c_str(), d, best->id, limit, kTargetPointRadii, kTargetPointMinMm);
    throw std::invalid_argument(std::string(text) + "; targets: " + list);
  }
  return best->id;
}

}  // namespace gw
