#pragma once
// Positions and unit tangents at fixed arc distances from the wire tip: what a fibre-Bragg
// shape sensor along the tip reports, and all the observation needs from the wire's shape.
#include <Eigen/Core>
#include <array>

#include "engine/wire/wire_model.hpp"
#include "engine/wire/wire_state.hpp"

namespace gw {

inline constexpr int kTipSampleCount = 3;

struct TipSamples {
  std::array<Eigen::Vector3d, kTipSampleCount> position;  // [0] = the tip itself
  std::array<Eigen::Vector3d, kTipSampleCount> tangent;   // unit, pointing distally
};

// Sample i sits i * spacing_mm (rest arc length) proximal of the tip, interpolated on the element
// chords of `state.x`; its tangent is that element's chord direction. No allocation.
void sample_tip(const WireModel& model, const WireState& state, double spacing_mm, TipSamples& out);

}  // namespace gw
