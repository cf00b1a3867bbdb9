#pragma once
// What an actor's action vector holds. Each layout has a name, recorded in the exported actor's JSON
// (`action_layout`) and in the server's `spec`:
//   guidewire-nav/act/1  [rotation]: the paper's task; the task pushes at the constant push speed
//   guidewire-nav/act/2  [rotation, insertion]: the insertion speed in [-1, 1] x push_mm_per_s while the
//                        actor is in control (issue 37 item 1b, docs/recovery.md "A learned push/pull
//                        actor"); needs the observation's push/pull entries (observation layout obs/5)
#include <string>

namespace gw {

// One env step's command. `rotation` in [-1, 1] x max_rotation_rad_per_s; `insertion` in [-1, 1] x
// push_mm_per_s, read only under act/2 (act/1 pushes at +1: the paper's constant push).
struct Action {
  double rotation = 0.0;
  double insertion = 1.0;
};

enum class ActionLayout {
  kRotation,           // act/1
  kRotationInsertion,  // act/2
};

const char* action_layout_name(ActionLayout layout);
// 1 or 2 values.
int action_layout_size(ActionLayout layout);
// The layout called `name`; throws std::invalid_argument naming the known layouts.
ActionLayout parse_action_layout(const std::string& name);

}  // namespace gw
