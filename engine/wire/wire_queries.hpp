#pragma once
// What observations need from the wire: the inserted part only, ordered proximal -> distal.
#include <Eigen/Core>
#include <vector>

#include "engine/wire/wire_state.hpp"

namespace gw {

// Positions of the nodes past the inlet (the free nodes), proximal -> distal; empty if none.
std::vector<Eigen::Vector3d> inserted_node_positions(const WireModel& model, const WireState& state);

// Distal tip position [mm].
Eigen::Vector3d tip_position(const WireModel& model, const WireState& state);

// Unit tangents (pointing distally) at the tip and at `count - 1` points `spacing_mm` apart behind it
// along the wire (arc length), from the node frames interpolated along each element. Points behind
// the proximal end are clamped to it. Throws std::invalid_argument for count < 1 or spacing < 0.
std::vector<Eigen::Vector3d> tip_tangents(const WireModel& model, const WireState& state, int count, double spacing_mm);

// Curvature vector at the distal tip [1/mm]: the bending rate (Darboux vector) averaged over the curved
// tip (params.tip_length_mm), crossed with the tip tangent; points where the tip bends towards,
// |k| = 0.2 at rest.
Eigen::Vector3d tip_curvature_vector(const WireModel& model, const WireState& state);

// Velocity of the distal tip [mm/s].
Eigen::Vector3d tip_velocity(const WireModel& model, const WireState& state);

// Unit tangent of node i's frame (local x axis).
Eigen::Vector3d node_tangent(const WireState& state, int i);

}  // namespace gw
