#include "base/util/parse_point.hpp"

#include <sstream>
#include <stdexcept>

namespace gw {

Eigen::Vector3d parse_point(const std::string& text, const std::string& flag) {
  std::istringstream s(text);
  double x = 0, y = 0, z = 0;
  char c1 = 0, c2 = 0;
  if (!(s >> x >> c1 >> y >> c2 >> z) || c1 != ',' || c2 != ',' || !(s >> std::ws).eof() ||
      !Eigen::Vector3d(x, y, z).allFinite())
    throw std::invalid_argument(flag + ": expected x,y,z (three finite numbers separated by commas, mm), got '" + text +
                                "'");
  return {x, y, z};
}

}  // namespace gw
