#pragma once
// O(N) solver for symmetric positive definite block-tridiagonal systems with 6x6 blocks
// (one block per wire node: 3 translations + 3 rotations), plus the selected blocks of the inverse
// that the contact compliance W = H A^-1 H^T needs.
#include <Eigen/Core>
#include <vector>

namespace gw {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

// The matrix: diag[i] = A(i,i), lower[i] = A(i+1,i) for i < n-1 (upper blocks are the transposes).
// Vectors only grow (resize keeps capacity), so re-assembling every step allocates nothing.
struct BlockTridiagonal {
  std::vector<Mat6> diag;
  std::vector<Mat6> lower;
  int n = 0;
  void resize(int size) {
    n = size;
    if (static_cast<int>(diag.size()) < n) diag.resize(n);
    if (static_cast<int>(lower.size()) < n) lower.resize(n);
    for (int i = 0; i < n; ++i) {
      diag[i].setZero();
      lower[i].setZero();
    }
  }
  int size() const { return n; }
};

// Block Thomas factorisation: Schur complements S_i = D_i - B_{i-1} S_{i-1}^-1 B_{i-1}^T, kept inverted,
// and G_i = S_i^-1 B_i^T (B_i = A(i+1,i)).
struct BlockTridiagonalFactor {
  std::vector<Mat6> s_inv;
  std::vector<Mat6> g;
  int n = 0;
  int size() const { return n; }
};

// Factorises `a`; returns false when a pivot block is not positive definite (singular / indefinite).
bool factor_block_tridiagonal(const BlockTridiagonal& a, BlockTridiagonalFactor& f);

// Solves A x = rhs in place (rhs has 6 * n rows) with the factorisation `f` of `a`.
void solve_block_tridiagonal(const BlockTridiagonal& a, const BlockTridiagonalFactor& f,
                             Eigen::Ref<Eigen::VectorXd> rhs);

// Diagonal blocks of A^-1 (Sigma_i = S_i^-1 + G_i Sigma_{i+1} G_i^T), in O(n). The off-diagonal blocks
// follow from them: (A^-1)(i,j) = (-G_i)(-G_{i+1})...(-G_{j-1}) Sigma_j for i < j.
void inverse_diagonal_blocks(const BlockTridiagonalFactor& f, std::vector<Mat6>& sigma);

}  // namespace gw
