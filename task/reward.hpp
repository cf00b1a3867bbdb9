#pragma once
// The reward of paper Eq. 3, with the orientation sigmoid's centre and slope as parameters.
#include <string>

namespace gw {

// What act/2's progress term is paid for (push_pull_reward's `new_depth`; act/1 ignores it).
enum class RewardProgress {
  kCommanded,  // the insertion commands summed past their deepest so far: every act/2 actor before 2026-12-07
  kCourse,     // the tip's projection on the target's course past its deepest so far, in full-speed steps of
               // advance: a push into a wrong child or into a jam earns (almost) nothing, and after a pull-back
               // out of a wrong child the correct child pays from its ostium on (under kCommanded only once the
               // commands are deeper than they went into the wrong child; results/generalist/README.md)
};

// r = 2 / (1 + exp(slope (omega - centre))) - 1  +  0.5 (1 - lambda_t / lambda_0)  -  0.2 |a_t|
// The paper's sigmoid is centre 0.1, slope 5 (the defaults). It is flat below omega ~ -0.5 (0.955 at
// -0.65, 0.992 at -1) while a rotation step costs 0.2 |a|, so it barely pays for the fine aim
// (omega near -1) that decides shallow branches; a shifted, steeper sigmoid (e.g. centre -0.5, slope 8)
// keeps paying down to omega ~ -0.9. The shape is a task setting so a policy's training records it.
struct RewardShape {
  double omega_centre = 0.1;
  double omega_slope = 5.0;
  RewardProgress progress = RewardProgress::kCommanded;
};

// "commanded" | "course"; throws std::invalid_argument for anything else.
RewardProgress parse_reward_progress(const std::string& text);
const char* reward_progress_name(RewardProgress progress);

// `lambda_ratio` is lambda_t / lambda_0, `action` the applied rotation action in [-1, 1].
double navigation_reward(double omega, double lambda_ratio, double action, const RewardShape& shape = {});

// The push/pull actor's reward (action layout act/2): the paper's progress term earned in proportion to
// `new_depth` in [0, 1], the part of a full-speed step by which the wire went deeper than ever before in the
// episode; the orientation term's change (below); the rotation effort as in Eq. 3; less `wrong_branch_cost` while the tip is in a wrong
// child; less `time_cost` every step. Why: with the speed in the actor's hands, Eq. 3's positive terms pay
// for every step, so holding still while aimed would pay forever; weighted by the forward insertion, pushing
// and pulling back in turn would (a first run learnt exactly that: docs/policy_history.md). Weighted by new
// depth, stopping and going back and forth earn nothing. But then stopping is free, and an actor that may
// enter a wrong child drifts to stopping (the 50k checkpoint of the first push/pull run did: results/push_pull);
// a time cost makes every step spent short of the target cost something (TaskConfig::reward_time_per_step).
//
// How the act/2 reward pays for the aim: by the orientation term's change over the step, O(omega) - O(omega_before),
// paid whatever the wire does; only the progress term is weighted by new depth. Why: weighted by new depth (the
// retired "depth" aim, docs/policy_history.md), the orientation term makes every push while omega is above the
// sigmoid's centre cost up to 1, where stopping costs only the time: an actor learns to stop, or to pull back,
// wherever pushing on turns omega the wrong way before it gets better (an S-curve before a fork), and training
// pulled the widened rotation actor's training episodes from 96% success to 40-78% (results/push_pull). A change
// telescopes: over an episode it sums to O(last) - O(first) whatever the path (potential-based shaping, Ng, Harada
// and Russell 1999), so it pays neither for holding an aim nor for going back and forth, and it costs a push only by
// the aim it loses, which turning back gains again.
double push_pull_reward(double omega, double omega_before, double lambda_ratio, double rotation, double new_depth,
                        bool in_wrong_branch, double wrong_branch_cost, double time_cost, const RewardShape& shape = {});

}  // namespace gw
