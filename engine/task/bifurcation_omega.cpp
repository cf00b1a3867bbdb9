#include "engine/task/bifurcation_omega.hpp"

#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/task/observation.hpp"

namespace gw {

namespace {

constexpr double kTwoPi = 6.283185307179586;

// JunctionModel::kGap: the unit direction opposite the middle of the widest angle between consecutive wrong
// directions about `normal` (zero ones, along the normal, left out); zero when none is left, the one itself
// when one is. A tip bent straight away from it bends into the middle of that widest angle.
Eigen::Vector3d widest_gap_wrong_direction(const Eigen::Vector3d& normal, const std::vector<Eigen::Vector3d>& wrong) {
  std::vector<const Eigen::Vector3d*> present;
  for (const Eigen::Vector3d& wp : wrong)
    if (wp.squaredNorm() > 0.25) present.push_back(&wp);
  if (present.empty()) return Eigen::Vector3d::Zero();
  if (present.size() == 1) return *present.front();
  const Eigen::Vector3d e1 = *present.front();
  const Eigen::Vector3d e2 = normal.cross(e1);
  std::vector<double> angle;
  for (const Eigen::Vector3d* wp : present) angle.push_back(std::atan2(wp->dot(e2), wp->dot(e1)));
  std::sort(angle.begin(), angle.end());
  double widest = -1.0, middle = 0.0;
  for (size_t i = 0; i < angle.size(); ++i) {
    const double next = i + 1 < angle.size() ? angle[i + 1] : angle.front() + kTwoPi;
    if (next - angle[i] > widest) {  // the first of equal widest gaps, in angle order from e1
      widest = next - angle[i];
      middle = angle[i] + 0.5 * widest;
    }
  }
  const double opposite = middle + 0.5 * kTwoPi;
  return std::cos(opposite) * e1 + std::sin(opposite) * e2;
}

}  // namespace

OmegaReading bifurcation_omega(const CourseBifurcation& b, const Eigen::Vector3d& curvature, double rest_curvature,
                               JunctionModel model) {
  OmegaReading r;
  if (b.wrong_in_plane.empty()) return r;
  if (model == JunctionModel::kGap && b.wrong_in_plane.size() > 1) {
    // k wrong directions: aim into the middle of the widest angle between them (one virtual wrong branch
    // opposite it), which stays an aim where their mean cancels.
    const Eigen::Vector3d wp = widest_gap_wrong_direction(b.omega_normal, b.wrong_in_plane);
    r.omega = wrong_branch_alignment(curvature, b.omega_normal, wp, rest_curvature);
    r.side = wrong_branch_side(curvature, b.omega_normal, wp, rest_curvature);
    return r;
  }
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
