#include "base/graph/descending_aorta_inlet.hpp"

#include <cstdio>

namespace gw {

std::optional<AortaAccess> descending_aorta_inlet(const CenterlineGraph& g, double wide_vessel_radius_mm) {
  const Terminal* widest = nullptr;
  for (const Terminal& t : g.targets)
    if (!widest || t.radius > widest->radius) widest = &t;
  if (!widest || widest->radius <= wide_vessel_radius_mm || widest->radius > g.inlet.radius) return std::nullopt;
  for (const Terminal& t : g.targets)
    if (&t != widest && kAortaOverBranches * t.radius > widest->radius) return std::nullopt;
  const TargetPath aorta = plan_path(g, widest->id);
  int great = 0;
  for (const PathBifurcation& b : aorta.bifurcations) great += static_cast<int>(b.wrong_children.size());
  if (great < 2) return std::nullopt;
  AortaAccess a;
  a.target = widest->id;
  a.position = widest->position;
  a.radius = widest->radius;
  a.ascending_radius = g.inlet.radius;
  a.great_vessels = great;
  a.doubtful = widest->radius >= kAortaEndsAlike * g.inlet.radius;
  char text[640];
  std::snprintf(text, sizeof text,
                "aortic arch: entered at the descending aorta (femoral access), the narrower of its two ends (%.2f, "
                "%.2f, %.2f), radius %.1f mm, %d vessels leaving between it and the wider end (%.2f, %.2f, %.2f), "
                "radius %.1f mm, taken for the ascending aorta%s; to enter elsewhere pass --inlet x,y,z (the wider "
                "end: --inlet %.2f,%.2f,%.2f)",
                a.position.x(), a.position.y(), a.position.z(), a.radius, great, g.inlet.position.x(),
                g.inlet.position.y(), g.inlet.position.z(), a.ascending_radius,
                a.doubtful ? " (the two ends are nearly as wide: which one descends is a guess)" : "",
                g.inlet.position.x(), g.inlet.position.y(), g.inlet.position.z());
  a.note = text;
  return a;
}

}  // namespace gw
