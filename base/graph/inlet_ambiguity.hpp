#pragma once
// Extraction without a given insertion point takes the widest vessel end as the inlet. That
// guess is right for clinical trees (the ostium or aorta is the widest end) and arbitrary for a
// tree of constant radius, where the wire would start from a branch end. This names the doubt.
#include <string>

#include "base/graph/centerline_graph.hpp"

namespace gw {

// A target end at least this fraction of the inlet's radius makes "the widest end" a guess.
inline constexpr double kInletAmbiguityRatio = 0.85;

// Empty when the inlet is clearly the widest end; else one sentence naming the rival target,
// both radii and the --inlet the user would pass to keep the guess.
std::string inlet_ambiguity(const CenterlineGraph& graph);

}  // namespace gw
