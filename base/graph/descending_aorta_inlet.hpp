#pragma once
// Femoral access on an aortic arch. Extraction without an insertion point takes the widest vessel end as the
// inlet. On an aortic arch that is the ascending aorta (wider than the descending aorta in adults, and in the
// generator's arches: 14.4 against 10 mm), while a wire from the groin enters at the descending aorta.
// Input: a graph extracted from its widest end, and the radius above which a vessel is wider than any coronary
// (TaskConfig::wide_vessel_radius_mm). Output: the end to enter at instead when the graph is an arch, else none.
// An arch: the widest target is wider than that radius and kAortaOverBranches times every other target, and
// at least two other vessels leave the way between it and the inlet (the great vessels). The descending aorta
// is then the narrower of the two aortic ends, the widest target. `doubtful` when the two ends are within
// kAortaEndsAlike of each other's radius: which one descends is a guess then.
#include <Eigen/Core>
#include <optional>
#include <string>

#include "base/graph/centerline_graph.hpp"

namespace gw {

inline constexpr double kAortaOverBranches = 1.25;
inline constexpr double kAortaEndsAlike = 0.9;

struct AortaAccess {
  int target = 0;                      // the descending aorta's end, a target of the widest-end graph
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double radius = 0, ascending_radius = 0;
  int great_vessels = 0;               // vessels leaving between the two aortic ends
  bool doubtful = false;
  std::string note;                    // one sentence: what was found, how, and the --inlet to go back
};

std::optional<AortaAccess> descending_aorta_inlet(const CenterlineGraph& graph, double wide_vessel_radius_mm);

}  // namespace gw
