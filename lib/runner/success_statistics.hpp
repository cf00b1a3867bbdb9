#pragma once
// How much a success rate over a few dozen seeded episodes can be trusted, and whether one
// controller really beats another on the same episodes. 50 episodes at 90% leave an interval
// about 20 points wide, so the table prints it instead of letting 88% vs 94% read as a ranking.
#include <nlohmann/json.hpp>

namespace gw {

struct RateInterval {
  double low = 0.0;   // in [0, 1]
  double high = 1.0;
};

// Wilson score interval for `successes` of `episodes` (95% with the default z). Chosen over the
// normal approximation because it stays inside [0, 1] and is not degenerate at 0 or n successes,
// which our rows hit (100% rows). episodes = 0 gives [0, 1]. Throws std::invalid_argument when
// successes is outside [0, episodes].
RateInterval wilson_interval(int successes, int episodes, double z = 1.959963984540054);

// Two controllers run on the same episodes (same anatomy, target and seed): how many each won that
// the other lost, and the exact two-sided sign test (McNemar's exact test) on those discordant pairs.
struct PairedComparison {
  int paired = 0;         // episodes present in both
  int only_first = 0;     // first succeeded, second did not
  int only_second = 0;    // second succeeded, first did not
  double sign_test_p = 1.0;
};

// Pairs the `results` arrays of two summaries (episode_batch's summarize_episodes) by
// (anatomy, target, seed); episodes found in only one of them are ignored.
PairedComparison compare_paired(const nlohmann::json& first_summary, const nlohmann::json& second_summary);

// Exact two-sided binomial sign test: probability, under p = 1/2, of a split of a + b discordant
// pairs at least as uneven as (a, b). 1 when a + b = 0.
double sign_test_p(int a, int b);

// Two rates from different episodes (ours against a paper's, which reports only its count): Fisher's
// exact two-sided test on the 2x2 table of successes and failures, conditioned on both margins. The
// probability, if both came from one rate, of a split at most as likely as the one seen. Throws
// std::invalid_argument when a count is outside [0, episodes].
double fisher_exact_p(int successes_a, int episodes_a, int successes_b, int episodes_b);

}  // namespace gw
