#pragma once
// What an actor's observation vector holds (observation.hpp): the plane omega is measured in, whether
// omega's sine follows it, and how a junction's wrong branches enter omega. Each combination an actor
// was trained on has a name, recorded in the exported actor's JSON (`obs_layout`) and in the server's
// `spec`; the task (TaskConfig::observation), the server and the Eigen runtime all read it from here:
//   guidewire-nav/obs/1  omega in the correct branch's normal plane (the paper's definition), 11 entries
//   guidewire-nav/obs/3  omega in the approach plane and its sine (omega_side), 12 entries (the shipped actor;
//                        TaskConfig's default)
//   guidewire-nav/obs/4  obs/3 with junctions combined (docs/junctions.md), 12 entries
//   guidewire-nav/obs/5  obs/3 + the last insertion action and a wrong-branch flag, 14 entries: the push/pull
//                        actor's (action layout act/2, action_layout.hpp; docs/recovery.md)
//   guidewire-nav/obs/6  obs/3 with k-way junctions (docs/junctions.md), 12 entries
//   guidewire-nav/obs/8  obs/5 + the tip's wall force, 15 entries: the generalist controller's (act/2; issue 64,
//                        docs/anatomy_pool.md)
// Retired (no shipped actor used them; docs/policy_history.md "Retired settings"): obs/2 (obs/3 without omega_side)
// and obs/7 (obs/5 and the time since the tip last progressed).
#include <string>

namespace gw {

inline constexpr int kThetaCount = 3;
// Every entry is computed on every step; a layout hands its first size() entries to the actor.
inline constexpr int kObservationSize = 2 * kThetaCount + 9;
inline constexpr int kPaperObservationSize = 2 * kThetaCount + 5;  // obs/1: without omega_side
inline constexpr int kSideObservationSize = kPaperObservationSize + 1;  // obs/3, obs/4, obs/6: with omega_side
inline constexpr int kPushPullObservationSize = kSideObservationSize + 2;  // obs/5: with the push/pull entries
inline constexpr int kTipForceObservationSize = kPushPullObservationSize + 1;  // obs/8: and the tip's wall force

// The plane omega is measured in (observation.hpp, omega).
enum class OmegaPlane {
  kCorrectBranch,  // paper 2.2.3: tip curvature and wrong direction w projected on the plane normal to the
                   // correct branch c. Blind where c is ~90 deg off the approach: the tip's bend then
                   // lies in that plane's normal and w_p ~ the approach axis, so omega ~ 0 for every roll
  kApproach,       // curvature and (w - c) projected on the plane normal to the approach direction p (the
                   // axis the proximal rotation rolls the tip bend around): -1 when the tip bends from the
                   // wrong towards the correct branch. Equals kCorrectBranch's reading when c is along p
};

// How the wrong branches of a junction enter omega (observation.hpp; issue 41, docs/junctions.md).
enum class JunctionModel {
  kSeparate,  // each bifurcation on its own; with several wrong children omega is the largest (the most
              // dangerous) one. The paper's task and every row of the results table
  kCombined,  // a bifurcation also counts the wrong children of the bifurcations that follow it along the
              // course within close_junction_diameters vessel diameters (closely spaced forks), and omega
              // is measured against the mean of the wrong directions (a k-way junction: the tip aims
              // away from all of them, reaching -1 where the max could not). Identical to kSeparate on a
              // two-way fork with no fork close behind it; measured worse than kSeparate where two close forks' wrong
              // branches lie on opposite sides (their mean cancels; results/junctions), so off by default
  kKWay,      // the mean of the wrong directions within one k-way junction only (kCombined's second half);
              // closely spaced forks each on their own, as kSeparate. Why: the close-forks row showed that
              // aiming at two forks together throws away which side each wrong branch is on, while the
              // separate reading aims away from one and then the next (results/junctions). Identical to
              // kSeparate on a tree of two-way forks and to kCombined on one without close forks
};

struct ObservationLayout {
  OmegaPlane omega_plane = OmegaPlane::kApproach;  // kCorrectBranch = the paper's definition (obs/1)
  bool omega_side = true;                          // obs/3 (the default), obs/4, obs/5, obs/6: omega's sine as a
                                                   // twelfth entry (false: obs/1, the paper's plane)
  JunctionModel junctions = JunctionModel::kSeparate;  // kCombined: obs/4, kKWay: obs/6
  bool push_pull = false;                          // obs/5: the insertion action and the wrong-branch flag
                                                   // as entries 13 and 14 (the act/2 actor's)
  bool tip_force = false;                          // obs/8: obs/5 and the tip's wall force as entry 15

  // The layout's name; throws std::invalid_argument for a combination no layout has (omega_side in the
  // paper's plane; the approach plane without omega_side; combined junctions without omega_side; push/pull
  // entries without obs/3), naming why.
  const char* name() const;
  // How many leading observation entries the actor takes: 11, 12 with omega_side, 14 with push_pull, 15 with
  // tip_force.
  int size() const;
  // The layout called `name`; throws std::invalid_argument naming the known layouts.
  static ObservationLayout parse(const std::string& name);
};

// "correct_branch" | "approach"; throws std::invalid_argument for anything else.
OmegaPlane parse_omega_plane(const std::string& text);
const char* omega_plane_name(OmegaPlane plane);

// "separate" | "combined" | "kway"; throws std::invalid_argument for anything else.
JunctionModel parse_junction_model(const std::string& text);
const char* junction_model_name(JunctionModel model);

}  // namespace gw
