#include "base/graph/inlet_ambiguity.hpp"

#include <cstdio>

namespace gw {

std::string inlet_ambiguity(const CenterlineGraph& g) {
  const Terminal* rival = nullptr;
  for (const Terminal& t : g.targets)
    if (t.radius >= kInletAmbiguityRatio * g.inlet.radius && (!rival || t.radius > rival->radius)) rival = &t;
  if (!rival) return {};
  char text[512];
  std::snprintf(text, sizeof text,
                "the inlet was guessed as the widest vessel end (%.2f, %.2f, %.2f), radius %.2f mm, but target %d "
                "(%.2f, %.2f, %.2f) is nearly as wide (%.2f mm); if the wire enters elsewhere, pass --inlet x,y,z "
                "(this guess: --inlet %.2f,%.2f,%.2f)",
                g.inlet.position.x(), g.inlet.position.y(), g.inlet.position.z(), g.inlet.radius, rival->id,
                rival->position.x(), rival->position.y(), rival->position.z(), rival->radius, g.inlet.position.x(),
                g.inlet.position.y(), g.inlet.position.z());
  return text;
}

}  // namespace gw
