#include "lib/runner/episode_force.hpp"

#include <algorithm>

namespace gw {

nlohmann::json episode_force(const EpisodeTrace& t, int first, int last) {
  const int n = static_cast<int>(t.wall_force_peak_node_mN.size());
  if (n == 0 || t.wall_force_peak_total_mN.size() != t.wall_force_peak_node_mN.size() ||
      t.wall_force_mean_total_mN.size() != t.wall_force_peak_node_mN.size() ||
      t.tip_force_mN.size() != t.wall_force_peak_node_mN.size())
    return nlohmann::json::object();
  first = std::max(first, 0);
  last = std::min(last, n - 1);
  if (last <= first) return nlohmann::json::object();
  double node = 0, total = 0, sum = 0, tip = 0;
  for (int f = first + 1; f <= last; ++f) {
    const auto i = static_cast<std::size_t>(f);
    node = std::max(node, t.wall_force_peak_node_mN[i]);
    total = std::max(total, t.wall_force_peak_total_mN[i]);
    tip = std::max(tip, t.tip_force_mN[i]);
    sum += t.wall_force_mean_total_mN[i];
  }
  nlohmann::json out = {{"peak_node_N", 1e-3 * node},
                        {"peak_total_N", 1e-3 * total},
                        {"mean_total_N", 1e-3 * sum / (last - first)},
                        {"peak_tip_N", 1e-3 * tip}};
  if (t.push_held_s.size() == t.wall_force_peak_node_mN.size()) {
    double held = 0;
    for (int f = first + 1; f <= last; ++f) held += t.push_held_s[static_cast<std::size_t>(f)];
    out["push_held_s"] = held;
  }
  return out;
}

}  // namespace gw
