#pragma once
// Who turns the wire during an episode: the SAC actor (Eigen runtime) or one of the two
// baselines the results table compares it with. The task decides when an action is applied
// (near bifurcations in trees); a controller maps an observation to a rotation in [-1, 1] and, for a
// push/pull actor (action layout act/2), an insertion in [-1, 1] (the others leave it at +1).
#include <memory>
#include <string>

#include "task/observation.hpp"

namespace gw {

class Controller {
 public:
  virtual ~Controller() = default;
  virtual const std::string& name() const = 0;
  // The action for observation `obs`.
  virtual Action act(const Observation& obs) = 0;
  // Called before each episode: a controller reused across a batch forgets the last one here.
  virtual void begin_episode() {}
  // Sets what the controller needs of the task's observation and action (an actor: the layouts it was
  // trained with). Build the task with the adapted config; baselines take the default.
  virtual void adapt(TaskConfig& /*config*/) const {}
};

// The exported SAC actor at `actor_path` (action layout act/1 or act/2, from its JSON). Throws
// std::runtime_error naming the file when it cannot be loaded or its sizes do not match its layouts.
std::unique_ptr<Controller> make_policy_controller(const std::string& actor_path);

// Lower anchor 1: never rotates (the wire goes where its start orientation and the wall send it).
std::unique_ptr<Controller> make_push_only_controller();

// Lower anchor 2: a hand-written rule on omega (tip curvature vs wrong-branch direction): rotate at
// full rate until the tip bends away from the wrong branch (omega <= release), then hold. -0.95 = within
// 18 degrees of straight away: measured 2026-11-27 (25-50 episodes per row), it beat -0.7 on var1
// (80 vs 60%), var2 (100 vs 96%), coronary (92 vs 76%) and deformed coronary (64 vs 56%) and tied
// elsewhere; a looser release leaves the tip half-aimed at shallow branches.
// omega says how far the bend is from the wrong branch, not on which side, so the rule turns one fixed
// way: `turn` +1 ("scripted-omega") or -1 ("scripted-omega-ccw", the same rule mirrored). Where it stops
// (just short of -1, on the side it came from) depends on that choice, and on a shallow fork that side
// can decide the branch: the table runs both so a baseline's lead is not read as skill when it is the
// direction (results table, 2026-11-30: coronary 94 vs 82%, deformed coronary 74 vs 58%).
inline constexpr double kScriptedOmegaRelease = -0.95;
std::unique_ptr<Controller> make_scripted_omega_controller(double release = kScriptedOmegaRelease, double turn = 1.0);

// The scripted rule itself, the one C++ implementation (the controller above and the aim-* rotation schedules;
// Python: guidewire_nav.baselines.scripted_omega_action). Inputs: omega (observation entry 9), the release
// threshold, the turn direction (+1 / -1). Output: the rotation action, `turn` while omega > release, else 0.
inline double scripted_omega_action(double omega, double release, double turn) { return omega > release ? turn : 0.0; }

// "policy" (needs `actor_path`) | "push-only" | "scripted-omega" | "scripted-omega-ccw" | a rotation schedule
// (rotation_schedules.hpp: aim-0.95, spin+1, wiggle, ...); throws std::invalid_argument otherwise.
std::unique_ptr<Controller> make_controller(const std::string& kind, const std::string& actor_path);

// The shipped default actor: $GW_POLICY if set, else policy/trained/sac_actor.json of the source tree.
std::string default_policy_path();

// A file shipped in the repository, e.g. "engine/wire/aortic_035_angled.json", as an absolute path.
std::string shipped_path(const std::string& relative);

// A path as results record it (results.json settings, navigate --json): an absolute path into the source tree
// becomes relative to it (shipped_path's inverse: "policy/trained/sac_actor.json"), so a committed result names
// no machine's folders; any other path is kept as given.
std::string recorded_path(const std::string& path);

// The actor `evaluate` runs on the sensitivity rows, trained on sensitivity/base only (the paper's
// section 3.1): sac_actor_base.json beside `policy_path`.
std::string base_policy_path(const std::string& policy_path);

}  // namespace gw
