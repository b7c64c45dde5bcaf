#include "numerics/sparse_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "geolens/core/errors.h"

namespace geolens {
namespace {

// A path graph's Laplacian plus `shift` on the diagonal, with `skew` added above the diagonal
// (0: symmetric).
Eigen::SparseMatrix<double> chain(int n, double shift, double skew) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + shift);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0 + skew);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// The reduced system solved densely: x_f = A_ff^-1 (b_f - A_fc x_c).
Eigen::MatrixXd dense_reference(const Eigen::SparseMatrix<double>& A,
                                const std::vector<char>& fixed, const Eigen::MatrixXd& b,
                                const Eigen::MatrixXd& x_fixed) {
  const Eigen::MatrixXd D(A);
  std::vector<int> free, given;
  for (int i = 0; i < int(fixed.size()); ++i) (fixed[size_t(i)] ? given : free).push_back(i);
  const Eigen::MatrixXd rhs = b(free, Eigen::all) - D(free, given) * x_fixed(given, Eigen::all);
  Eigen::MatrixXd x = x_fixed;
  x(free, Eigen::all) = D(free, free).fullPivLu().solve(rhs);
  return x;
}

TEST(DirichletSolver, MatchesTheDenseReducedSystemSymmetricAndGeneral) {
  const int n = 40;
  std::vector<char> fixed(n, 0);
  fixed[0] = fixed[17] = fixed[n - 1] = 1;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  const Eigen::MatrixXd b = Eigen::MatrixXd::NullaryExpr(n, 2, [&] { return u(rng); });
  const Eigen::MatrixXd x_fixed = Eigen::MatrixXd::NullaryExpr(n, 2, [&] { return u(rng); });
  for (const auto matrix :
       {DirichletSolver::Matrix::kSymmetric, DirichletSolver::Matrix::kGeneral}) {
    const bool general = matrix == DirichletSolver::Matrix::kGeneral;
    const Eigen::SparseMatrix<double> A = chain(n, 0.0, general ? 0.4 : 0.0);
    const DirichletSolver solver(A, fixed, matrix);
    EXPECT_EQ(solver.free_count(), n - 3);
    const Eigen::MatrixXd x = solver.solve(b, x_fixed);
    EXPECT_LT((x - dense_reference(A, fixed, b, x_fixed)).cwiseAbs().maxCoeff(), 1e-9);
    for (int i : {0, 17, n - 1}) EXPECT_EQ(x.row(i), x_fixed.row(i));
  }
}

TEST(DirichletSolver, RefactorizeTakesNewValuesOnThePattern) {
  const int n = 30;
  std::vector<char> fixed(n, 0);
  fixed[0] = 1;
  const Eigen::MatrixXd b = Eigen::MatrixXd::Ones(n, 1), x_fixed = Eigen::MatrixXd::Zero(n, 1);
  for (const auto matrix :
       {DirichletSolver::Matrix::kSymmetric, DirichletSolver::Matrix::kGeneral}) {
    const bool general = matrix == DirichletSolver::Matrix::kGeneral;
    DirichletSolver solver(chain(n, 0.0, general ? 0.3 : 0.0), fixed, matrix);
    const Eigen::SparseMatrix<double> changed = chain(n, 0.5, general ? 0.3 : 0.0);
    solver.refactorize(changed);
    EXPECT_LT((solver.solve(b, x_fixed) - dense_reference(changed, fixed, b, x_fixed))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-9);
    EXPECT_THROW(solver.refactorize(chain(n + 1, 0.0, 0.0)), InvalidInput);
  }
}

TEST(DirichletSolver, ASingularReducedSystemIsASolverError) {
  const int n = 10;  // a Laplacian with nothing fixed is singular
  Eigen::SparseMatrix<double> A = chain(n, 0.0, 0.0);
  A.coeffRef(0, 0) = 1;
  A.coeffRef(n - 1, n - 1) = 1;
  const std::vector<char> none(n, 0);
  EXPECT_THROW(DirichletSolver(A, none, DirichletSolver::Matrix::kSymmetric), SolverError);
  EXPECT_THROW(DirichletSolver(A, none, DirichletSolver::Matrix::kGeneral), SolverError);
}

TEST(DirichletSolver, EverythingFixedReturnsTheFixedValues) {
  const std::vector<char> all(5, 1);
  const Eigen::MatrixXd x_fixed = Eigen::MatrixXd::Random(5, 2);
  EXPECT_EQ(DirichletSolver(chain(5, 0, 0), all).solve(Eigen::MatrixXd::Zero(5, 2), x_fixed),
            x_fixed);
  EXPECT_THROW(DirichletSolver(chain(5, 0, 0), std::vector<char>(4, 0)), InvalidInput);
}

}  // namespace
}  // namespace geolens
