// course_shape_at (task/course_shape.hpp).
// Inputs: anatomy with a moving scene, its GraphMotion, the task config, target id, time t [s].
// Output: the course shape at t: the mapped graph, its branch polylines and the course built on them.
#include "task/course_shape.hpp"

namespace gw {

void course_shape_at(const Anatomy& anatomy, const GraphMotion& motion, const TaskConfig& config, int target_id,
                     double t, CourseShape& out) {
  Anatomy& a = out.anatomy;
  if (!out.valid) {
    a.name = anatomy.name;
    a.mesh_path = anatomy.mesh_path;
    a.scene = anatomy.scene;
  }
  graph_at(anatomy.graph, *anatomy.scene, motion, t, a.graph);
  a.branch_lines.resize(a.graph.branches.size());
  for (size_t b = 0; b < a.graph.branches.size(); ++b) a.branch_lines[b] = make_polyline(a.graph.branches[b].points);
  out.course = make_course(a.graph, a.branch_lines, target_id, config);
  out.time = t;
  out.valid = true;
}

}  // namespace gw
