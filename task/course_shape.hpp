#pragma once
// One course in the wall's current shape (issue 36): the graph mapped through the wall's displacement at
// the wire state's time (graph_motion.hpp) and the course rebuilt on it with make_course, so lambda,
// omega, the control spheres, the wrong-branch test and "target reached" all read the vessel where it is
// now. Part of the episode's state (EpisodeState::shape), recomputed every observation; unused on a
// static wall.
#include "base/graph/centerline_graph.hpp"
#include "task/anatomy.hpp"
#include "task/course.hpp"
#include "task/graph_motion.hpp"
#include "task/task_config.hpp"

namespace gw {

struct CourseShape {
  bool valid = false;                 // false: the wall is static, read the task's course
  double time = 0.0;                  // the time the shape is of [s]
  Anatomy anatomy;                    // the anatomy at `time`: graph mapped, branch_lines rebuilt on it (name
                                      // and scene as the task's)
  Course course;                      // make_course(anatomy.graph, anatomy.branch_lines, target, config)
};

// Inputs: the anatomy (rest graph, moving scene), its GraphMotion, the task config, the target, a time
// t [s]. Output: `out` at time t (reused between calls). Throws what make_course throws.
void course_shape_at(const Anatomy& anatomy, const GraphMotion& motion, const TaskConfig& config, int target_id,
                     double t, CourseShape& out);

}  // namespace gw
