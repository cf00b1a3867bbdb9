#include "task/tip_samples.hpp"

#include <stdexcept>

namespace gw {

void sample_tip(const WireModel& model, const WireState& state, double spacing_mm, TipSamples& out) {
  const int n = static_cast<int>(state.x.size());
  if (n < 2 || static_cast<int>(model.arc_from_tip.size()) != n)
    throw std::invalid_argument("sample_tip: wire state does not match its model");
  int e = n - 2;  // element (e, e+1), walked proximally as the samples move back
  for (int i = 0; i < kTipSampleCount; ++i) {
    const double d = i * spacing_mm;
    while (e > 0 && model.arc_from_tip[e] < d) --e;
    const double a0 = model.arc_from_tip[e], a1 = model.arc_from_tip[e + 1];  // a0 >= d >= a1 inside
    const Eigen::Vector3d chord = state.x[e + 1] - state.x[e];
    const double u = a0 > a1 ? std::min(1.0, std::max(0.0, (a0 - d) / (a0 - a1))) : 1.0;
    out.position[i] = state.x[e] + u * chord;
    const double len = chord.norm();
    out.tangent[i] = len > 1e-12 ? Eigen::Vector3d(chord / len) : Eigen::Vector3d::UnitX();
  }
}

}  // namespace gw
