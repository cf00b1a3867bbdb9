// The O(N) block-tridiagonal solver against dense LDLT and SuiteSparse CHOLMOD on the real wire system.
// GCC 12 + AVX-512 reports a false -Wmaybe-uninitialized inside Eigen's dense GEMM kernels (system
// header avx512fintrin.h); only this test uses dynamic dense products (the dense reference inverse).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <limits>
#include <random>

#include "engine/sim/assemble_system.hpp"
#include "engine/solver/block_tridiagonal.hpp"
#include "engine/wire/wire_state.hpp"
#include "random_systems.hpp"

using namespace gw;
using test::random_spd;
using test::to_dense;

namespace {

// A bent, twisted, moving wire: the system of a real step, not of a wire at rest.
WireState disturbed_state(const WireModel& model) {
  WireState s = make_initial_state(model, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.3, 1, 0.2), 0.7, 80.0);
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0, 1);
  const int k = first_free_node(model, s);
  for (int i = k; i < model.nodes; ++i) {
    s.x[i] += 0.05 * Eigen::Vector3d(g(rng), g(rng), g(rng)) + 0.002 * (i - k) * (i - k) * Eigen::Vector3d::UnitZ();
    s.q[i] = (Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * g(rng), Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized())) *
              s.q[i]).normalized();
    s.v[i] = Eigen::Vector3d(g(rng), g(rng), g(rng));
    s.w[i] = Eigen::Vector3d(g(rng), g(rng), g(rng));
  }
  return s;
}

}  // namespace

TEST_CASE("block-tridiagonal solve equals dense LDLT on random SPD systems", "[solver]") {
  std::mt19937 rng(1);
  for (int n : {1, 2, 5, 40}) {
    BlockTridiagonal a = random_spd(n, rng);
    BlockTridiagonalFactor f;
    REQUIRE(factor_block_tridiagonal(a, f));
    Eigen::VectorXd b = Eigen::VectorXd::Random(6 * n);
    Eigen::VectorXd x = b;
    solve_block_tridiagonal(a, f, x);
    const Eigen::MatrixXd d = to_dense(a);
    const Eigen::VectorXd ref = d.ldlt().solve(b);
    CHECK((x - ref).norm() <= 1e-12 * ref.norm());
    // Selected inverse: diagonal blocks and the chained off-diagonal ones.
    std::vector<Mat6> sigma;
    inverse_diagonal_blocks(f, sigma);
    const Eigen::MatrixXd inv = d.inverse();
    for (int i = 0; i < n; ++i) CHECK((sigma[i] - inv.block<6, 6>(6 * i, 6 * i)).norm() <= 1e-12 * inv.norm());
    for (int i = 0; i < n; ++i) CHECK(f.s_inv[i] == f.s_inv[i].transpose());  // the pivots' inverses, exactly symmetric
    if (n >= 5) {
      Mat6 chain = -f.g[1];
      for (int j = 2; j < 4; ++j) chain = (chain * (-f.g[j])).eval();
      CHECK((chain * sigma[4] - inv.block<6, 6>(6, 24)).norm() <= 1e-12 * inv.norm());
    }
  }
}

TEST_CASE("a pivot that is not positive definite is reported, not solved", "[solver]") {
  BlockTridiagonal a;
  a.resize(2);
  a.diag[0] = Mat6::Identity();
  a.diag[1] = -Mat6::Identity();
  BlockTridiagonalFactor f;
  CHECK_FALSE(factor_block_tridiagonal(a, f));
}

TEST_CASE("BTD and CHOLMOD give the same dv for the wire's implicit Euler system", "[solver][cholmod]") {
  const WireModel model = make_wire_model(default_wire_params(), 0.01);
  const WireState s = disturbed_state(model);
  DynamicsSystem sys;
  assemble_system(model, s, 12.0, 0.8, model.h, sys);
  const int nf = sys.a.size();
  REQUIRE(nf > 30);

  Eigen::SparseMatrix<double> sp;
  Eigen::VectorXd rhs;
  assemble_system_sparse(model, s, 12.0, 0.8, sp, rhs);
  REQUIRE(sp.rows() == 6 * nf);
  // Same system: the sparse assembly path agrees with the block one.
  CHECK((rhs - sys.rhs.head(6 * nf)).norm() <= 1e-12 * rhs.norm());
  CHECK((Eigen::MatrixXd(sp) - to_dense(sys.a)).norm() <= 1e-12 * Eigen::MatrixXd(sp).norm());

  BlockTridiagonalFactor f;
  REQUIRE(factor_block_tridiagonal(sys.a, f));
  Eigen::VectorXd x = sys.rhs.head(6 * nf);
  solve_block_tridiagonal(sys.a, f, x);

  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> chol;
  chol.compute(sp);
  REQUIRE(chol.info() == Eigen::Success);
  const Eigen::VectorXd y = chol.solve(rhs);
  REQUIRE(chol.info() == Eigen::Success);
  // Round-off agreement: the relative difference is bounded by cond(A) * eps (the system mixes mm and
  // rad, stiff axial and soft bending modes, so cond(A) is large).
  const Eigen::MatrixXd dense = Eigen::MatrixXd(sp);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, Eigen::EigenvaluesOnly);
  const double cond = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
  const double diff = (x - y).norm() / y.norm();
  INFO("relative difference " << diff << ", cond(A) " << cond);
  CHECK(diff <= 10.0 * cond * std::numeric_limits<double>::epsilon());
  // Both actually solve the system.
  CHECK((sp * x - rhs).norm() <= 1e-9 * rhs.norm());
}
