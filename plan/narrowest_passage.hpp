#pragma once
// narrowest_passage: whether the course to a target narrows below the wire somewhere, which no maneuver can
// overcome (the walls are rigid), so the planner can say "unreachable, and why" instead of spending its budget.
// Input: the centerline graph (per-point distance to the wall), the target, the wire's radius, and the least length of
// course over which the lumen must stay narrower than the wire to count (a single dipping point of an extraction
// is not a wall across the lumen). Output: the longest such stretch (where it starts along the course, its
// length, the narrowest radius in it), or none. Throws std::invalid_argument for an unknown target (plan_path's).
#include <optional>

#include "base/graph/centerline_graph.hpp"

namespace gw {

inline constexpr double kNarrowPassageMinMm = 1.0;  // course length narrower than the wire for a passage to count

struct NarrowPassage {
  double start_mm = 0.0;   // along the course from the inlet
  double length_mm = 0.0;  // of the stretch narrower than the wire
  double radius_mm = 0.0;  // the narrowest lumen radius in it
};

std::optional<NarrowPassage> narrowest_passage(const CenterlineGraph& graph, int target_id, double wire_radius_mm,
                                               double min_length_mm = kNarrowPassageMinMm);

}  // namespace gw
