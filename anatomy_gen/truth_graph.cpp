#include "anatomy_gen/truth_graph.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace gw {
namespace {

// Samples [i0, i1] of a branch, resampled at (at most) `spacing` along the arclength.
CenterlineBranch resample(const BranchCurve& c, int i0, int i1, double spacing) {
  CenterlineBranch out;
  const double s0 = c.arclength[i0], s1 = c.arclength[i1];
  const int steps = std::max(1, static_cast<int>(std::ceil((s1 - s0) / spacing - 1e-9)));
  int j = i0;
  for (int k = 0; k <= steps; ++k) {
    if (k == 0 || k == steps) {
      const int i = k == 0 ? i0 : i1;
      out.points.push_back(c.points[i]);
      out.radii.push_back(c.radii[i]);
      continue;
    }
    const double s = s0 + (s1 - s0) * k / steps;
    while (j + 1 < i1 && c.arclength[j + 1] < s) ++j;
    const double len = c.arclength[j + 1] - c.arclength[j];
    const double t = len > 0.0 ? std::clamp((s - c.arclength[j]) / len, 0.0, 1.0) : 0.0;
    out.points.push_back((1.0 - t) * c.points[j] + t * c.points[j + 1]);
    out.radii.push_back((1.0 - t) * c.radii[j] + t * c.radii[j + 1]);
  }
  return out;
}

}  // namespace

CenterlineGraph build_truth_graph(const TreeGeometry& g, double spacing) {
  CenterlineGraph graph;
  const int n = static_cast<int>(g.branches.size());
  // Pieces of every spec branch: cut at interior child samples.
  std::vector<std::vector<int>> cuts(n);                 // piece boundaries (sample indices)
  std::vector<std::map<int, int>> piece_ending_at(n);    // sample -> graph branch ending there
  std::vector<std::map<int, int>> piece_starting_at(n);  // sample -> graph branch starting there
  for (int b = 0; b < n; ++b) {
    const BranchCurve& c = g.branches[b];
    const int last = static_cast<int>(c.points.size()) - 1;
    cuts[b].push_back(0);
    for (int s : c.child_samples)
      if (s > 0 && s < last) cuts[b].push_back(s);
    cuts[b].push_back(last);
    for (size_t k = 0; k + 1 < cuts[b].size(); ++k) {
      CenterlineBranch piece = resample(c, cuts[b][k], cuts[b][k + 1], spacing);
      piece.id = static_cast<int>(graph.branches.size());
      if (k > 0) piece.parent = piece_ending_at[b][cuts[b][k]];
      else if (c.parent >= 0) piece.parent = piece_ending_at[c.parent].at(c.parent_sample);
      piece_ending_at[b][cuts[b][k + 1]] = piece.id;
      piece_starting_at[b][cuts[b][k]] = piece.id;
      graph.branches.push_back(std::move(piece));
    }
  }
  // One bifurcation per distinct point where children leave a spec branch.
  for (int b = 0; b < n; ++b) {
    const BranchCurve& c = g.branches[b];
    for (int s : c.child_samples) {
      Bifurcation bif;
      bif.id = static_cast<int>(graph.bifurcations.size());
      bif.position = c.points[s];
      bif.parent = piece_ending_at[b].at(s);
      if (piece_starting_at[b].count(s)) bif.children.push_back(piece_starting_at[b][s]);
      for (int k = 0; k < n; ++k)
        if (g.branches[k].parent == b && g.branches[k].parent_sample == s) bif.children.push_back(piece_starting_at[k].at(0));
      std::sort(bif.children.begin(), bif.children.end());
      graph.bifurcations.push_back(bif);
    }
  }
  // Round to 1e-6 mm (a nanometre): readable files, far below any tolerance.
  auto round6 = [](Eigen::Vector3d& p) { p = (p * 1e6).array().round() / 1e6; };
  for (CenterlineBranch& b : graph.branches) {
    for (Eigen::Vector3d& p : b.points) round6(p);
    for (double& r : b.radii) r = std::round(r * 1e6) / 1e6;
  }
  for (Bifurcation& b : graph.bifurcations) round6(b.position);
  const BranchCurve& root = g.branches.front();
  graph.inlet.id = 0;
  graph.inlet.position = graph.branches.front().points.front();
  graph.inlet.branch = 0;
  graph.inlet.radius = graph.branches.front().radii.front();
  graph.inlet_direction = (root.points[1] - root.points[0]).normalized();  // dense samples: exact tangent
  number_targets(graph);
  return graph;
}

}  // namespace gw
