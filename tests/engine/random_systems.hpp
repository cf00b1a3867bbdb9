#pragma once
// Random symmetric positive definite block-tridiagonal systems and their dense form, for the solver
// and contact tests.
#include <Eigen/Core>
#include <random>

#include "engine/solver/block_tridiagonal.hpp"

namespace gw::test {

inline Eigen::MatrixXd to_dense(const BlockTridiagonal& a) {
  const int n = a.size();
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (int i = 0; i < n; ++i) {
    d.block<6, 6>(6 * i, 6 * i) = a.diag[i];
    if (i + 1 < n) {
      d.block<6, 6>(6 * (i + 1), 6 * i) = a.lower[i];
      d.block<6, 6>(6 * i, 6 * (i + 1)) = a.lower[i].transpose();
    }
  }
  return d;
}

// Diagonally dominant blocks (r r^T + 14 I) with random off-diagonal coupling: SPD, well coupled.
inline BlockTridiagonal random_spd(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  BlockTridiagonal a;
  a.resize(n);
  for (int i = 0; i < n; ++i) {
    Mat6 r = Mat6::NullaryExpr([&](Eigen::Index, Eigen::Index) { return u(rng); });
    a.diag[i] = r * r.transpose() + 14.0 * Mat6::Identity();
    if (i + 1 < n) a.lower[i] = Mat6::NullaryExpr([&](Eigen::Index, Eigen::Index) { return u(rng); });
  }
  return a;
}

}  // namespace gw::test
