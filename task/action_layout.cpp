#include "task/action_layout.hpp"

#include <stdexcept>

namespace gw {

const char* action_layout_name(ActionLayout layout) {
  return layout == ActionLayout::kRotation ? "guidewire-nav/act/1" : "guidewire-nav/act/2";
}

int action_layout_size(ActionLayout layout) { return layout == ActionLayout::kRotation ? 1 : 2; }

ActionLayout parse_action_layout(const std::string& name) {
  if (name == "guidewire-nav/act/1") return ActionLayout::kRotation;
  if (name == "guidewire-nav/act/2") return ActionLayout::kRotationInsertion;
  throw std::invalid_argument("action layout '" + name + "' is not one of guidewire-nav/act/1, guidewire-nav/act/2");
}

}  // namespace gw
