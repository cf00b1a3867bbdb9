#include "base/util/median.hpp"

#include <algorithm>
#include <limits>

namespace gw {

double median(std::vector<double> sample) {
  if (sample.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = sample.begin() + static_cast<long>(sample.size() / 2);
  std::nth_element(sample.begin(), mid, sample.end());
  return *mid;
}

}  // namespace gw
