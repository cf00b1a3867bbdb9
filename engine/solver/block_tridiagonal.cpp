#include "engine/solver/block_tridiagonal.hpp"

#include <Eigen/Cholesky>

namespace gw {

bool factor_block_tridiagonal(const BlockTridiagonal& a, BlockTridiagonalFactor& f) {
  const int n = a.size();
  f.n = n;
  if (static_cast<int>(f.s_inv.size()) < n) f.s_inv.resize(n);
  if (static_cast<int>(f.g.size()) < n) f.g.resize(n);
  Mat6 s;
  for (int i = 0; i < n; ++i) {
    s = a.diag[i];
    if (i > 0) s.noalias() -= a.lower[i - 1] * f.g[i - 1];
    Eigen::LLT<Mat6> llt(s);
    if (llt.info() != Eigen::Success) return false;
    f.s_inv[i].setIdentity();
    llt.solveInPlace(f.s_inv[i]);
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
