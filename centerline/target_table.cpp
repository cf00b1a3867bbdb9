#include "centerline/target_table.hpp"

#include <cstdio>
#include <sstream>

namespace gw {

std::string format_target_table(const CenterlineGraph& g) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "inlet at (%.2f, %.2f, %.2f) mm, radius %.2f mm; %zu target(s), %zu bifurcation(s)\n",
                g.inlet.position.x(), g.inlet.position.y(), g.inlet.position.z(), g.inlet.radius, g.targets.size(),
                g.bifurcations.size());
  out << line;
  std::snprintf(line, sizeof line, "%4s  %-30s  %10s  %8s  %s\n", "id", "position (mm)", "path (mm)", "radius",
                "bifurcations on the way: id(branch taken)");
  out << line;
  for (const auto& t : g.targets) {
    const TargetPath path = plan_path(g, t.id);
    std::ostringstream bifs;
    for (const auto& b : path.bifurcations) bifs << (bifs.tellp() > 0 ? " " : "") << b.bifurcation << "(" << b.correct_child << ")";
    char pos[64];
    std::snprintf(pos, sizeof pos, "(%.2f, %.2f, %.2f)", t.position.x(), t.position.y(), t.position.z());
    std::snprintf(line, sizeof line, "%4d  %-30s  %10.2f  %8.2f  %s\n", t.id, pos, path.length, t.radius,
                  path.bifurcations.empty() ? "-" : bifs.str().c_str());
    out << line;
  }
  return out.str();
}

}  // namespace gw
