#include "task/navigation_task.hpp"

#include <stdexcept>

namespace gw {

NavigationTask make_navigation_task(const TaskConfig& config, const WireParams& wire, std::vector<Anatomy> anatomies) {
  check_task_config(config);
  if (anatomies.empty()) throw std::invalid_argument("navigation task needs at least one anatomy");
  NavigationTask task;
  task.config = config;
  const WireModel run_wire = make_wire_model(wire, config.dt_s);
  task.anatomies = std::move(anatomies);
  for (const Anatomy& a : task.anatomies) {
    task.wires.push_back(a.wire ? make_wire_model(*a.wire, config.dt_s) : run_wire);
    std::vector<Course> courses;
    for (const Terminal& t : a.graph.targets) {
      try {
        courses.push_back(make_course(a.graph, a.branch_lines, t.id, config));
      } catch (const std::exception& e) {
        throw std::invalid_argument(a.name + ": target " + std::to_string(t.id) + ": " + e.what());
      }
    }
    task.courses.push_back(std::move(courses));
    task.graph_motions.push_back(a.scene && a.scene->motion ? make_graph_motion(a.graph, *a.scene) : GraphMotion{});
  }
  return task;
}

int find_anatomy(const NavigationTask& task, const std::string& name) {
  for (size_t i = 0; i < task.anatomies.size(); ++i)
    if (task.anatomies[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace gw
