#pragma once
// What `navigate --out DIR` leaves for a person and for ParaView:
//   vessel.vtp, centerline.vtp                  the wall and the extracted centerline graph
//   target<T>_path.vtp, target<T>.png           per target: the planned path, and the biplane figure
//                                               with every episode's tip trace and final wire
//   episode<K>_target<T>.json / .vtp / _wire.vtp  per episode: the trajectory (JSON and VTK)
#include <string>
#include <vector>

#include "apps/report/trajectory.hpp"
#include "apps/runner/navigation_anatomy.hpp"

namespace gw {

// Writes the files above into `dir` (created if missing) and returns their paths. Throws
// ReportError / std::runtime_error "<path>: <problem>" when a file cannot be written.
std::vector<std::string> write_navigation_outputs(const std::string& dir, const NavigationAnatomy& anatomy,
                                                  const std::vector<EpisodeTrace>& traces,
                                                  const std::vector<std::string>& title_lines);

}  // namespace gw
