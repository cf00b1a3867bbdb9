#include "plan/narrowest_passage.hpp"

#include <algorithm>

namespace gw {

std::optional<NarrowPassage> narrowest_passage(const CenterlineGraph& graph, int target_id, double wire_radius_mm,
                                               double min_length_mm) {
  const TargetPath path = plan_path(graph, target_id);
  std::optional<NarrowPassage> best;
  NarrowPassage run;
  bool inside = false;
  double arc = 0.0;
  for (std::size_t k = 0; k < path.points.size() && k < path.radii.size(); ++k) {
    if (k > 0) arc += (path.points[k] - path.points[k - 1]).norm();
    if (path.radii[k] < wire_radius_mm) {
      if (!inside) run = {arc, 0.0, path.radii[k]};
      inside = true;
      run.length_mm = arc - run.start_mm;
      run.radius_mm = std::min(run.radius_mm, path.radii[k]);
      if (run.length_mm >= min_length_mm && (!best || run.length_mm > best->length_mm)) best = run;
    } else {
      inside = false;
    }
  }
  return best;
}

}  // namespace gw
