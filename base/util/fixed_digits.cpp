#include "base/util/fixed_digits.hpp"

#include <sstream>

namespace gw {

std::string fixed_digits(double value, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << value;
  return s.str();
}

}  // namespace gw
