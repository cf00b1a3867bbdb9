#pragma once
// omega and omega_side (observation.hpp entries 9 and 11) of the tip against one bifurcation of the
// course, with one or several wrong branches (TaskConfig::observation.junctions, docs/junctions.md).
#include <Eigen/Core>

#include "task/course.hpp"

namespace gw {

struct OmegaReading {
  double omega = 0.0;  // in [-1, 1]; -1: the tip bends straight away from the wrong branch(es)
  double side = 0.0;   // omega's sine about the plane normal (which way a roll lowers omega)
};

// Inputs: `b` (its omega_normal and wrong_in_plane), `curvature` (tip curvature vector, 1/mm),
// `rest_curvature` (the tip's, 1/mm), `model`. kSeparate: the largest omega over the wrong directions
// and the side of that same one (the paper with one wrong branch); kCombined and kKWay with two or more
// wrong directions: omega and side against their mean direction, both 0 where they cancel (which
// directions `b` holds is make_course's: kCombined adds close forks', kKWay does not).
// Output: omega and side; both 0 when `b` has no wrong direction.
OmegaReading bifurcation_omega(const CourseBifurcation& b, const Eigen::Vector3d& curvature, double rest_curvature,
                               JunctionModel model);

}  // namespace gw
