#pragma once
// The task's "wrong branch" verdict (paper 2.2: an episode fails once the tip enters a wrong child).
#include <Eigen/Core>

#include "task/anatomy.hpp"
#include "task/course.hpp"
#include "task/task_config.hpp"

namespace gw {

// Inputs: the task constants, the anatomy (its branch polylines), the course, the tip and its distance
// to the course's centreline.
// Output: the index (into course.bifurcations) of the bifurcation whose wrong child the tip is in, or -1.
// In a wrong child = nearer its centreline than to any part of the course (the whole course, not just the
// continuation: a wrong child may bend back towards the access vessel, e.g. an S-shaped pattern) and far
// enough along it: TaskScale::kFixed, wrong_branch_depth_mm from the bifurcation centre; kVessel (the
// course's resolved scale), that far past the child's ostium and inside its lumen.
int wrong_branch_entered(const TaskConfig& config, const Anatomy& anatomy, const Course& course,
                         const Eigen::Vector3d& tip, double course_distance);

}  // namespace gw
