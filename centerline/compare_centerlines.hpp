#pragma once
// Accuracy of an extracted centerline graph against ground truth (same schema), in
// units of the local true radius so thin and wide vessels weigh alike.
#include <string>

#include "base/graph/centerline_graph.hpp"

namespace gw {

struct CenterlineAccuracy {
  int terminals = 0, true_terminals = 0;        // inlet + targets
  int bifurcations = 0, true_bifurcations = 0;
  bool same_topology = false;  // equal counts, and every true terminal has its own
                               // extracted terminal within 2 local radii
  long points = 0;             // extracted points measured
  // Distance of each extracted point to the nearest true centerline segment / the true
  // radius there.
  double mean_distance = 0, p95_distance = 0, max_distance = 0;
  // |extracted radius - true radius| / true radius at the same nearest location.
  double mean_radius_error = 0, p95_radius_error = 0;
  // Each true bifurcation to its nearest extracted one / true radius there (max over all;
  // 0 when there are none).
  double max_bifurcation_offset = 0;
  // Each true terminal to its matched extracted terminal / true radius (max over all).
  double max_terminal_offset = 0;
};

// Compares `extracted` with `truth`. Both must have at least one branch with points.
CenterlineAccuracy compare_centerlines(const CenterlineGraph& extracted, const CenterlineGraph& truth);

// One JSON object with every field (for benchmarks and test logs).
std::string accuracy_to_json(const CenterlineAccuracy& accuracy);

}  // namespace gw
