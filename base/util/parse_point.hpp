#pragma once
// parse_point: a point given on a command line, "x,y,z" in mm (an --inlet, a --target-point).
// Inputs: the text; the flag it came with, named in the error. Output: the point. Throws
// std::invalid_argument "FLAG: expected x,y,z (three finite numbers separated by commas, mm), got 'TEXT'" for
// anything else (fewer numbers, other separators, trailing text, NaN or infinity).
#include <Eigen/Core>
#include <string>

namespace gw {

Eigen::Vector3d parse_point(const std::string& text, const std::string& flag);

}  // namespace gw
