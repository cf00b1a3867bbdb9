#include "lib/report/palette.hpp"

#include <algorithm>
#include <cmath>

namespace gw::palette {

Rgb time_color(double s) {
  static constexpr double kStops[5][3] = {
      {13, 8, 135}, {126, 3, 168}, {204, 71, 120}, {248, 149, 64}, {240, 220, 33}};
  if (!std::isfinite(s)) s = 0.0;
  s = std::clamp(s, 0.0, 1.0) * 4.0;
  const int i = std::min(static_cast<int>(s), 3);
  const double f = s - i;
  auto mix = [&](int c) { return static_cast<std::uint8_t>(std::lround(kStops[i][c] * (1 - f) + kStops[i + 1][c] * f)); };
  return {mix(0), mix(1), mix(2)};
}

}  // namespace gw::palette
