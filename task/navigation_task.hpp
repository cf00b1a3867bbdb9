#pragma once
// The navigation task model (like mjModel): everything constant across episodes — the task
// configuration, the anatomies, the wire model each is navigated with and, for every target, its prepared course.
// Episodes (episode.hpp) hold pointers into it: keep the task alive and unmodified while they run.
#include <string>
#include <vector>

#include "task/anatomy.hpp"
#include "task/course.hpp"
#include "task/graph_motion.hpp"
#include "task/task_config.hpp"
#include "engine/wire/wire_model.hpp"
#include "engine/wire/wire_params.hpp"

namespace gw {

struct NavigationTask {
  TaskConfig config;
  std::vector<Anatomy> anatomies;
  std::vector<WireModel> wires;  // wires[a]: the wire anatomy a is navigated with (its own, else the run's)
  std::vector<std::vector<Course>> courses;  // courses[a][k] leads to target k + 1 of anatomy a
  // Per anatomy: how its centerline follows a moving wall (issue 36; graph_motion.hpp); empty (points = 0)
  // when its wall is static (anatomy.scene has no motion), and the episodes then read `courses` alone.
  std::vector<GraphMotion> graph_motions;
};

// Checks `config`, builds the wire models (dt = config.dt_s: an anatomy's own wire, Anatomy::wire, else `wire`),
// every course (on the rest graph) and, for an
// anatomy whose scene moves, its GraphMotion. Throws
// std::invalid_argument for a bad config, no anatomies, or an anatomy whose target cannot be planned.
NavigationTask make_navigation_task(const TaskConfig& config, const WireParams& wire, std::vector<Anatomy> anatomies);

// The wire model anatomy `a` is navigated with.
inline const WireModel& wire_of(const NavigationTask& task, int a) { return task.wires[static_cast<size_t>(a)]; }

// Index of the anatomy called `name`, or -1.
int find_anatomy(const NavigationTask& task, const std::string& name);

}  // namespace gw
