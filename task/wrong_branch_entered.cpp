#include "task/wrong_branch_entered.hpp"

namespace gw {

int wrong_branch_entered(const TaskConfig& config, const Anatomy& anatomy, const Course& course,
                         const Eigen::Vector3d& tip, double course_distance) {
  for (size_t k = 0; k < course.bifurcations.size(); ++k) {
    const CourseBifurcation& b = course.bifurcations[k];
    for (size_t j = 0; j < b.wrong_branches.size(); ++j) {
      const PolylineProjection pw =
          project_onto_polyline(anatomy.branch_lines[static_cast<size_t>(b.wrong_branches[j])], tip);
      if (pw.distance >= course_distance) continue;
      if (!course.vessel_scale) {
        if (pw.arc >= config.wrong_branch_depth_mm) return static_cast<int>(k);
        continue;
      }
      const BranchLumen& lumen = b.wrong_lumens[j];
      if (pw.arc >= lumen.ostium_arc + config.wrong_branch_depth_mm && pw.distance <= radius_at(lumen.profile, pw.arc))
        return static_cast<int>(k);
    }
  }
  return -1;
}

}  // namespace gw
