#pragma once
// Colours of the biplane figure (tests look pixels up by these).
#include <string>

#include "lib/report/image.hpp"

namespace gw::palette {

inline constexpr Rgb kBackground{255, 255, 255};
inline constexpr Rgb kPanelBorder{170, 170, 170};
inline constexpr Rgb kVesselFill{214, 214, 214};  // one wall layer; overlapping vessels are darker
inline constexpr Rgb kVesselEdge{150, 150, 150};  // silhouette outline
inline constexpr Rgb kPath{30, 90, 220};
inline constexpr Rgb kInlet{0, 120, 130};
inline constexpr Rgb kTarget{225, 20, 20};
inline constexpr Rgb kOtherTarget{105, 105, 105};
inline constexpr Rgb kBifurcation{125, 40, 165};
inline constexpr Rgb kTipPush{245, 140, 20};
inline constexpr Rgb kTipAgent{0, 175, 80};
inline constexpr Rgb kWire{0, 0, 0};
inline constexpr Rgb kText{25, 25, 25};

// Colour of an outcome ("success", "wrong_branch", ...); dark grey for anything else.
inline Rgb outcome_color(const std::string& outcome) {
  if (outcome == "success") return {0, 150, 60};
  if (outcome == "wrong_branch") return {200, 20, 70};
  if (outcome == "stuck") return {225, 115, 0};
  if (outcome == "timeout") return {150, 110, 0};
  if (outcome == "diverged") return {160, 0, 160};
  return {80, 80, 80};
}

// Tip colour at normalised time s in [0, 1] (a plasma-like ramp: dark violet -> yellow).
Rgb time_color(double s);

}  // namespace gw::palette
