#include "lib/runner/success_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace gw {

RateInterval wilson_interval(int successes, int episodes, double z) {
  if (episodes < 0 || successes < 0 || successes > episodes)
    throw std::invalid_argument("wilson_interval: " + std::to_string(successes) + " successes of " +
                                std::to_string(episodes) + " episodes");
  if (episodes == 0) return {};
  const double n = episodes, p = successes / n, z2 = z * z;
  const double centre = (p + z2 / (2 * n)) / (1 + z2 / n);
  const double half = z / (1 + z2 / n) * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

double sign_test_p(int a, int b) {
  const int n = a + b;
  if (n == 0) return 1.0;
  // P(X <= min(a, b)) for X ~ Binomial(n, 1/2), doubled; summed in logs so n in the thousands is fine.
  const int k_max = std::min(a, b);
  double tail = 0.0;
  for (int k = 0; k <= k_max; ++k)
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) - n * std::log(2.0));
  return std::min(1.0, 2.0 * tail);
}

double fisher_exact_p(int successes_a, int episodes_a, int successes_b, int episodes_b) {
  for (const auto& [k, n] : {std::pair{successes_a, episodes_a}, std::pair{successes_b, episodes_b}})
    if (n < 0 || k < 0 || k > n)
      throw std::invalid_argument("fisher_exact_p: " + std::to_string(k) + " successes of " + std::to_string(n) +
                                  " episodes");
  // Given both row totals and the total successes K, the first row's successes x is hypergeometric.
  const int n1 = episodes_a, n2 = episodes_b, K = successes_a + successes_b;
  auto log_choose = [](int n, int k) { return std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0); };
  auto log_p = [&](int x) { return log_choose(n1, x) + log_choose(n2, K - x) - log_choose(n1 + n2, K); };
  const double seen = log_p(successes_a);
  double p = 0.0;
  for (int x = std::max(0, K - n2); x <= std::min(K, n1); ++x)
    if (log_p(x) <= seen + 1e-7) p += std::exp(log_p(x));  // the tolerance keeps ties that rounding splits
  return std::min(1.0, p);
}

PairedComparison compare_paired(const nlohmann::json& first, const nlohmann::json& second) {
  using Key = std::tuple<std::string, int, std::uint64_t>;
  auto key_of = [](const nlohmann::json& ep) {
    return Key{ep.value("anatomy", ""), ep.value("target", 0), ep.value("seed", std::uint64_t{0})};
  };
  std::map<Key, bool> second_success;
  if (second.contains("results"))
    for (const nlohmann::json& ep : second["results"]) second_success[key_of(ep)] = ep.value("outcome", "") == "success";
  PairedComparison c;
  if (first.contains("results"))
    for (const nlohmann::json& ep : first["results"]) {
      const auto it = second_success.find(key_of(ep));
      if (it == second_success.end()) continue;
      ++c.paired;
      const bool a = ep.value("outcome", "") == "success", b = it->second;
      c.only_first += a && !b;
      c.only_second += b && !a;
    }
  c.sign_test_p = sign_test_p(c.only_first, c.only_second);
  return c;
}

}  // namespace gw
