#pragma once
// The reward of paper Eq. 3.

namespace gw {

// r = 2 / (1 + exp(5 (omega - 0.1))) - 1  +  0.5 (1 - lambda_t / lambda_0)  -  0.2 |a_t|
// `lambda_ratio` is lambda_t / lambda_0, `action` the applied rotation action in [-1, 1].
double navigation_reward(double omega, double lambda_ratio, double action);

}  // namespace gw
