#include "task/bifurcation_omega.hpp"

#include "task/observation.hpp"

namespace gw {

OmegaReading bifurcation_omega(const CourseBifurcation& b, const Eigen::Vector3d& curvature, double rest_curvature,
                               JunctionModel model) {
  OmegaReading r;
  if (b.wrong_in_plane.empty()) return r;
  if (model != JunctionModel::kSeparate && b.wrong_in_plane.size() > 1) {
    // k wrong directions: aim away from their mean (zero where they cancel, e.g. the middle exit of a
    // planar trifurcation: no bend is better than another there, as for a wrong branch along the normal).
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& wp : b.wrong_in_plane) mean += wp;
    const double len = mean.norm();
    const Eigen::Vector3d wp = len > 1e-6 ? Eigen::Vector3d(mean / len) : Eigen::Vector3d::Zero();
    r.omega = wrong_branch_alignment(curvature, b.omega_normal, wp, rest_curvature);
    r.side = wrong_branch_side(curvature, b.omega_normal, wp, rest_curvature);
    return r;
  }
  r.omega = -1.0;
  for (const Eigen::Vector3d& wp : b.wrong_in_plane) {
    const double w = wrong_branch_alignment(curvature, b.omega_normal, wp, rest_curvature);
    if (w < r.omega) continue;
    r.omega = w;  // the side of the same (most dangerous) wrong branch
    r.side = wrong_branch_side(curvature, b.omega_normal, wp, rest_curvature);
  }
  return r;
}

}  // namespace gw
