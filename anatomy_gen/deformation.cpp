#include "anatomy_gen/deformation.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "anatomy_gen/catmull_rom.hpp"
#include "anatomy_gen/tree_geometry.hpp"

namespace gw {

Eigen::Vector3d deform_point(const DeformationSpec& d, const Eigen::Vector3d& x, double phase) {
  const Eigen::Vector3d a = d.axis.normalized();
  const Eigen::Vector3d y = x - d.center;
  const double h = y.dot(a);
  const Eigen::Vector3d radial = (1.0 - phase * d.radial_contraction) * (y - h * a);
  const double theta = phase * d.twist_deg_per_cm * (h / 10.0) * M_PI / 180.0;
  const Eigen::Vector3d turned = Eigen::AngleAxisd(theta, a) * radial;
  return d.center + turned + (1.0 - phase * d.axial_shortening) * h * a;
}

TreeSpec deform_spec(const TreeSpec& spec, const DeformationSpec& field, double phase) {
  TreeSpec out = spec;
  out.deformation = DeformationSpec{};
  // Where each child leaves its parent, as a spline parameter: invariant under the map.
  std::vector<double> attach(spec.branches.size(), 0.0);
  for (size_t b = 1; b < spec.branches.size(); ++b)
    attach[b] = locate_on_branch(spec.branches[spec.branches[b].parent], spec.branches[b].points.front()).u;
  for (BranchSpec& b : out.branches)
    for (Eigen::Vector3d& p : b.points) p = deform_point(field, p, phase);
  for (size_t b = 1; b < out.branches.size(); ++b)
    out.branches[b].points.front() = catmull_rom_point(out.branches[out.branches[b].parent].points, attach[b]);
  return out;
}

void deform_centerline(CenterlineGraph& g, const DeformationSpec& field, double phase) {
  auto move = [&](Eigen::Vector3d& p) { p = deform_point(field, p, phase); };
  move(g.inlet.position);
  for (Terminal& t : g.targets) move(t.position);
  for (Bifurcation& b : g.bifurcations) move(b.position);
  for (CenterlineBranch& b : g.branches)
    for (Eigen::Vector3d& p : b.points) move(p);
  if (!g.branches.empty() && g.branches.front().points.size() >= 2)
    g.inlet_direction = (g.branches.front().points[1] - g.branches.front().points[0]).normalized();
}

}  // namespace gw
