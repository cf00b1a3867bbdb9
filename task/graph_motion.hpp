#pragma once
// The task's geometry on a moving wall (issue 36, docs/beating_heart.md): every point of an anatomy's
// centerline graph (inlet, branch points, bifurcation centres, targets) takes the wall's displacement, so
// the course, the control spheres and the targets are where the vessel is at the wire state's time.
// GraphMotion is constant (part of the model, built once per anatomy); the time is the state's.
#include <Eigen/Core>
#include <vector>

#include "base/graph/centerline_graph.hpp"
#include "engine/scene/vessel_scene.hpp"

namespace gw {

struct GraphMotion {
  int points = 0;  // graph points, in graph_point_order: inlet, branches' points, bifurcations, targets
  // Phase surfaces only (their displacement is known at the wall's vertices alone): per point, the wall
  // vertices it follows and their weights (CSR: [begin[i], begin[i + 1])); empty for fields defined
  // everywhere (rigid, cardiac), which map a point with the very formula that moves the wall.
  std::vector<int> begin, vertex;
  std::vector<double> weight;
};

// Inputs: the rest graph and its scene (scene.motion required). Output: the motion of the graph's points;
// for phase surfaces each point follows its kGraphMotionVertices nearest rest vertices, weighted by
// inverse distance (a point on a vertex follows that vertex alone, exactly). Throws std::invalid_argument
// for a scene without motion.
inline constexpr int kGraphMotionVertices = 8;
GraphMotion make_graph_motion(const CenterlineGraph& rest, const VesselScene& scene);

// Inputs: the rest graph, its moving scene, its GraphMotion, a time t [s]. Output: `out`, the graph with
// every point at its position at t (ids, radii and topology as in `rest`; `out` is reused, so a caller that
// maps every step does not allocate). A point of the field's own map is X + D(X, t), the wall's formula.
void graph_at(const CenterlineGraph& rest, const VesselScene& scene, const GraphMotion& motion, double t,
              CenterlineGraph& out);

// The graph's points in the order GraphMotion counts them (inlet, branches, bifurcations, targets).
std::vector<Eigen::Vector3d> graph_points(const CenterlineGraph& graph);

}  // namespace gw
