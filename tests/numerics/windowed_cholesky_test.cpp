#include "numerics/windowed_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>

#include "geolens/core/errors.h"

namespace geolens {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Step = WindowedCholesky::Step;

constexpr int kSide = 40;  // a kSide x kSide grid graph

// A grid-graph Laplacian plus a small diagonal (positive definite), its edge weights scaled by
// 1 + bump inside a disk of radius `radius` around (cx, cy) (radius 0: no bump), as a lens
// lifting a part of the flattening matrix. The pattern never depends on the bump.
SpMat matrix(double cx, double cy, double radius, double bump) {
  std::vector<Eigen::Triplet<double>> entries;
  auto weight = [&](int i, int j) {
    const double x = 0.5 * (i % kSide + j % kSide), y = 0.5 * (i / kSide + j / kSide);
    const double d = std::hypot(x - cx, y - cy);
    return 1.0 + (d < radius ? bump * (1 - d / radius) : 0.0);
  };
  for (int i = 0; i < kSide * kSide; ++i) {
    entries.emplace_back(i, i, 0.01);
    for (const int j : {i + 1, i + kSide}) {
      if ((j == i + 1 && j % kSide == 0) || j >= kSide * kSide) continue;
      const double w = weight(i, j);
      entries.emplace_back(i, i, w);
      entries.emplace_back(j, j, w);
      entries.emplace_back(i, j, -w);
      entries.emplace_back(j, i, -w);
    }
  }
  SpMat A(kSide * kSide, kSide * kSide);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

Eigen::MatrixXd rhs() {
  Eigen::MatrixXd b(kSide * kSide, 2);
  for (int i = 0; i < b.rows(); ++i) b.row(i) << std::sin(0.1 * i), std::cos(0.37 * i);
  return b;
}

// The largest difference to a fresh factorization's solution, relative to its size.
double error(const WindowedCholesky& solver, const SpMat& A) {
  const Eigen::MatrixXd reference = Eigen::SimplicialLLT<SpMat>(A).solve(rhs());
  return (solver.solve(rhs()) - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

TEST(WindowedCholesky, AMovingBumpRefactorizesOnlyItsWindowAndSolvesExactly) {
  WindowedCholesky solver(matrix(0, 0, 0, 0));
  EXPECT_EQ(solver.last_step(), Step::kNone);
  EXPECT_LT(error(solver, matrix(0, 0, 0, 0)), 1e-10);

  SpMat A = matrix(12, 20, 5, 3);
  solver.refactorize(A);
  EXPECT_EQ(solver.last_step(), Step::kFull);  // a first change: refactorized whole
  EXPECT_LT(error(solver, A), 1e-10);

  A = matrix(12.5, 20, 5, 3);
  solver.refactorize(A);
  EXPECT_EQ(solver.last_step(), Step::kRebuild);  // changing again: a window around the change
  const int window = solver.window_size();
  EXPECT_GT(window, 0);
  EXPECT_LT(window, kSide * kSide / 4);
  EXPECT_LT(error(solver, A), 1e-10);

  for (const double x : {13.0, 13.5, 12.0}) {  // small moves stay in the window
    A = matrix(x, 20, 5, 3);
    solver.refactorize(A);
    EXPECT_EQ(solver.last_step(), Step::kWindow) << x;
    EXPECT_EQ(solver.window_size(), window);
    EXPECT_LT(error(solver, A), 1e-10) << x;
  }
  solver.refactorize(A);  // the same values again
  EXPECT_EQ(solver.last_step(), Step::kNone);
  EXPECT_LT(error(solver, A), 1e-10);

  A = matrix(30, 28, 5, 3);  // a jump out of the window: a new one
  solver.refactorize(A);
  EXPECT_EQ(solver.last_step(), Step::kRebuild);
  EXPECT_LT(error(solver, A), 1e-10);
  A = matrix(30, 28.5, 5, 6);  // moved and taller: inside the new window
  solver.refactorize(A);
  EXPECT_EQ(solver.last_step(), Step::kWindow);
  EXPECT_LT(error(solver, A), 1e-10);
}

TEST(WindowedCholesky, AFocusCentresTheWindowOnWhereChangesWillBe) {
  // After a jump, the rows that changed hold the old place too; the focus names the new one.
  const SpMat before = matrix(8, 8, 5, 3);
  WindowedCholesky with_focus(before), without_focus(before);
  for (WindowedCholesky* solver : {&with_focus, &without_focus})
    solver->refactorize(matrix(8.5, 8, 5, 3));  // kFull
  const SpMat after = matrix(31, 31, 5, 3);
  std::vector<char> focus(kSide * kSide, 0);
  for (int i = 0; i < kSide * kSide; ++i)
    focus[size_t(i)] = std::hypot(i % kSide - 31.0, i / kSide - 31.0) < 6;
  with_focus.refactorize(after, focus);
  without_focus.refactorize(after);
  EXPECT_EQ(with_focus.last_step(), Step::kRebuild);
  EXPECT_EQ(without_focus.last_step(), Step::kRebuild);
  EXPECT_LT(with_focus.window_size(), 0.7 * without_focus.window_size());
  EXPECT_LT(error(with_focus, after), 1e-10);
  EXPECT_LT(error(without_focus, after), 1e-10);
}

TEST(WindowedCholesky, AChangeEverywhereFallsBackToTheWholeMatrix) {
  WindowedCholesky solver(matrix(0, 0, 0, 0));
  solver.refactorize(matrix(20, 20, 100, 1));
  solver.refactorize(matrix(20, 20, 100, 2));
  EXPECT_EQ(solver.last_step(), Step::kFull);
  EXPECT_EQ(solver.window_size(), 0);
  EXPECT_LT(error(solver, matrix(20, 20, 100, 2)), 1e-10);
}

TEST(WindowedCholesky, RefusesBadInput) {
  const SpMat A = matrix(0, 0, 0, 0);
  EXPECT_THROW(WindowedCholesky(A, -1), InvalidInput);
  EXPECT_THROW(WindowedCholesky(SpMat(3, 4)), InvalidInput);
  WindowedCholesky solver(A);
  EXPECT_THROW(solver.refactorize(SpMat(5, 5)), InvalidInput);
  EXPECT_THROW(solver.refactorize(A, std::vector<char>(3, 1)), InvalidInput);
  EXPECT_THROW(solver.solve(Eigen::MatrixXd::Zero(3, 1)), InvalidInput);
  SpMat indefinite = A;
  indefinite.coeffRef(0, 0) = -5;
  EXPECT_THROW(WindowedCholesky{indefinite}, SolverError);
  // A window's block that is not positive definite is refused too.
  solver.refactorize(matrix(20, 20, 4, 1));
  solver.refactorize(matrix(20, 20, 4, 2));
  ASSERT_EQ(solver.last_step(), Step::kRebuild);
  SpMat broken = matrix(20, 20, 4, 2);
  broken.coeffRef(20 * kSide + 20, 20 * kSide + 20) = -50;
  EXPECT_THROW(solver.refactorize(broken), SolverError);
}

}  // namespace
}  // namespace geolens
