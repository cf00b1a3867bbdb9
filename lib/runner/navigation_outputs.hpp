#pragma once
// What `navigate --out DIR` leaves for a person and for ParaView (VTK files are zlib-compressed
// binary VTK XML, lib/report/vtp_document.hpp):
//   vessel.vtp, centerline.vtp                  the wall (its rest shape when it beats) and the
//                                               extracted centerline graph
//   target<T>_path.vtp, target<T>.png           per target: the planned path, and the biplane figure
//                                               with every episode's tip trace and final wire; on a
//                                               beating wall the grey silhouette is the end-diastolic
//                                               wall and an outline shows it at end-systole
//   episode<K>_target<T>.json / .vtp            per episode: the trajectory (JSON; VTK tip trace and
//                                               final wire)
//   episode<K>_target<T>_reshaped.*            the same for a tip reshape's second pass (navigate
//                                               --reshape-tip), when the first did not reach the target
//   episode<K>_target<T>.pvd + episode<K>_target<T>/wire_<frame>.vtp
//                                               per episode with recorded wire shapes: a ParaView time
//                                               series, the wire (and the tip's way so far) at every
//                                               recorded frame, with the wall: vessel.vtp when static,
//                                               when it beats wall/phase_<phase x 1e9>.vtp, its surface
//                                               at that frame's cycle phase (one file per distinct
//                                               phase, shared by all episodes; wall/time_<ns>.vtp for a
//                                               wall that drifts instead of beating)
#include <string>
#include <vector>

#include "lib/report/trajectory.hpp"
#include "lib/runner/navigation_anatomy.hpp"
#include "engine/scene/vessel_scene.hpp"

namespace gw {

// Writes the files above into `dir` (created if missing, with the per-episode folders) and returns
// their paths. `wall`: the scene the episodes ran in; with a motion (VesselScene::motion) the wall
// beats and its surface is written per recorded frame; null or static: nav.mesh, as it is. Throws
// ReportError / std::runtime_error "<path>: <problem>" when a file cannot be written.
std::vector<std::string> write_navigation_outputs(const std::string& dir, const NavigationAnatomy& anatomy,
                                                  const std::vector<EpisodeTrace>& traces,
                                                  const std::vector<std::string>& title_lines,
                                                  const VesselScene* wall = nullptr);

// How often navigate records the wire shape (TraceOptions::wire_shape_every, env steps): every 25
// on a static wall; on a beating one about 8 times per cycle (every 3 steps of 0.04 s at 60 bpm, 2 at
// 100 bpm), so the series samples the motion instead of seeing the same phase each time.
int wire_shape_stride(const VesselScene* wall, double env_step_s);

// The surface of a moving wall at time t: the scene's rest mesh with every vertex moved by the
// motion (wall_vertex_position). The rest mesh itself when the scene has no motion.
TriangleMesh wall_mesh_at(const VesselScene& scene, double t);

// The first time >= 0 at which a moving wall's cycle is at `phase` (0 = end-diastole,
// systole_fraction = end-systole). Requires scene.motion with a positive heart rate.
double wall_time_at_phase(const VesselScene& scene, double phase);

}  // namespace gw
