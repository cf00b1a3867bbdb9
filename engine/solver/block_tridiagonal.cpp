#include "engine/solver/block_tridiagonal.hpp"

#include <cmath>

namespace gw {

namespace {

// The inverse of a symmetric positive definite 6x6 block through its Cholesky factor S = L L^T:
// S^-1 = L^-T L^-1, written out for the fixed size (Eigen's LLT solveInPlace on an identity goes through its
// blocked dynamic-size triangular solver). Only the lower triangle of S is read; the result is exactly
// symmetric (the lower triangle computed, mirrored). False when a pivot is not positive.
bool invert_spd6(const Mat6& s, Mat6& inv) {
  double l[6][6] = {};
  for (int j = 0; j < 6; ++j) {
    double d = s(j, j);
    for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
    if (!(d > 0)) return false;
    const double ljj = std::sqrt(d);
    l[j][j] = ljj;
    for (int i = j + 1; i < 6; ++i) {
      double v = s(i, j);
      for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
      l[i][j] = v / ljj;
    }
  }
  double m[6][6] = {};  // M = L^-1, lower triangular
  for (int j = 0; j < 6; ++j) {
    m[j][j] = 1.0 / l[j][j];
    for (int i = j + 1; i < 6; ++i) {
      double v = 0;
      for (int k = j; k < i; ++k) v -= l[i][k] * m[k][j];
      m[i][j] = v / l[i][i];
    }
  }
  for (int i = 0; i < 6; ++i)  // (M^T M)(i, j) = sum_{k >= max(i, j)} M(k, i) M(k, j)
    for (int j = 0; j <= i; ++j) {
      double v = 0;
      for (int k = i; k < 6; ++k) v += m[k][i] * m[k][j];
      inv(i, j) = inv(j, i) = v;
    }
  return true;
}

}  // namespace

bool factor_block_tridiagonal(const BlockTridiagonal& a, BlockTridiagonalFactor& f) {
  const int n = a.size();
  f.n = n;
  if (static_cast<int>(f.s_inv.size()) < n) f.s_inv.resize(n);
  if (static_cast<int>(f.g.size()) < n) f.g.resize(n);
  Mat6 s;
  for (int i = 0; i < n; ++i) {
    s = a.diag[i];
    if (i > 0) s.noalias() -= a.lower[i - 1] * f.g[i - 1];
    if (!invert_spd6(s, f.s_inv[i])) return false;
    if (i + 1 < n) f.g[i].noalias() = f.s_inv[i] * a.lower[i].transpose();
  }
  return true;
}

void solve_block_tridiagonal(const BlockTridiagonal& a, const BlockTridiagonalFactor& f,
                             Eigen::Ref<Eigen::VectorXd> x) {
  const int n = f.size();
  Vec6 y;
  // Forward: z_i = S_i^-1 (r_i - B_{i-1} z_{i-1}).
  for (int i = 0; i < n; ++i) {
    y = x.segment<6>(6 * i);
    if (i > 0) y.noalias() -= a.lower[i - 1] * x.segment<6>(6 * (i - 1));
    x.segment<6>(6 * i).noalias() = f.s_inv[i] * y;
  }
  // Backward: x_i = z_i - G_i x_{i+1}.
  for (int i = n - 2; i >= 0; --i) x.segment<6>(6 * i).noalias() -= f.g[i] * x.segment<6>(6 * (i + 1));
}

void inverse_diagonal_blocks(const BlockTridiagonalFactor& f, std::vector<Mat6>& sigma) {
  const int n = f.size();
  if (static_cast<int>(sigma.size()) < n) sigma.resize(n);
  if (n == 0) return;
  sigma[n - 1] = f.s_inv[n - 1];
  Mat6 t;
  for (int i = n - 2; i >= 0; --i) {
    t.noalias() = f.g[i] * sigma[i + 1];
    sigma[i] = f.s_inv[i];
    sigma[i].noalias() += t * f.g[i].transpose();
  }
}

}  // namespace gw
