#pragma once
// median: the middle value of a sample, the one median every radius and noise estimate uses.
// Input: the sample (taken by value; reordered). Output: its element of rank size/2 (for an even
// size the upper of the two middle values, no averaging); NaN for an empty sample.
#include <vector>

namespace gw {

double median(std::vector<double> sample);

}  // namespace gw
