#pragma once
// Safety figures of one physics step: how hard the wire presses on the vessel wall. The force the wire
// exerts on the wall is, by Newton's third law, the wall's force on the wire (WireState::contact_force,
// normal and friction, per node, in mN) with the sign turned: the magnitudes below are the same.
#include "engine/wire/wire_model.hpp"
#include "engine/wire/wire_state.hpp"

namespace gw {

// Contact points at element midpoints share their force between the element's two nodes, so the tip's
// force is taken over the nodes within this arc of the distal end (the last two 0.5 mm tip elements).
inline constexpr double kTipForceLengthMm = 1.0;

// Wall forces above this count as unsafe: 1.5 N, the vessel-rupture threshold used in recent autonomous
// navigation work (the engine's unit is mN). The safety figures, the tip-force observation's scale and the
// reward's force cost all use it.
inline constexpr double kRuptureForceN = 1.5;

struct WallForce {
  double peak_node_mN = 0.0;  // the largest |contact_force| of a single node
  double total_mN = 0.0;      // sum over the nodes of |contact_force|
  double tip_mN = 0.0;        // |sum of contact_force| over the nodes within kTipForceLengthMm of the tip
};

// Inputs: the wire model and a state after a step. Output: the figures of that step's contacts (all 0
// when the wire touched nothing, or before any step).
WallForce wall_force(const WireModel& model, const WireState& state);

}  // namespace gw
