#pragma once
#include <string>

#include "policy/actor_mlp.hpp"

namespace gw {

/// Format version string this loader accepts (see policy/README.md).
inline constexpr const char* kActorFormat = "guidewire-nav/actor/1";

/// Loads an actor JSON file (format kActorFormat). Throws std::runtime_error naming the file
/// and the field on: unreadable/invalid JSON, unknown format version, unknown activation,
/// non-finite numbers, layer shapes that do not chain, obs/action size mismatches.
ActorMLP load_actor(const std::string& path);

/// Same as load_actor but from JSON text; `source` names it in error messages.
ActorMLP parse_actor(const std::string& json_text, const std::string& source);

}  // namespace gw
