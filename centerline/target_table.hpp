#pragma once
// The readable target list printed by `centerline --list`.
#include <string>

#include "base/graph/centerline_graph.hpp"

namespace gw {

// One header line for the inlet, then one row per target: id, position (mm), path length
// from the inlet (mm), and the bifurcations met on the way as "id(branch taken)".
std::string format_target_table(const CenterlineGraph& graph);

}  // namespace gw
