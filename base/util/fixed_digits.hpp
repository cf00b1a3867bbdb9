#pragma once
// fixed_digits: a number in fixed notation with `digits` decimals, for messages ("0.120 mm").
// Input: the value, the decimals. Output: the text.
#include <string>

namespace gw {

std::string fixed_digits(double value, int digits = 2);

}  // namespace gw
