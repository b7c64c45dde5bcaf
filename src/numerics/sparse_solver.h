#pragma once
// Sparse linear systems with Dirichlet (fixed-value) conditions, factorized once and solved many
// times.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <limits>
#include <memory>
#include <vector>

namespace geolens {

class WindowedCholesky;  // private: src/numerics/windowed_cholesky.h

/// Solves A x = b for the free entries of x, the fixed entries given: the reduced system
/// A_ff x_f = b_f - A_fc x_c. For a symmetric positive semidefinite A (n x n) with A_ff positive
/// definite, by sparse Cholesky factorization (WindowedCholesky: after a change confined to a
/// few rows, only a window around them is refactorized); for a general A (A_ff invertible), by
/// sparse LU.
class DirichletSolver {
 public:
  enum class Matrix { kSymmetric, kGeneral };

  /// @param A       n x n system matrix
  /// @param fixed   n flags, non-zero where the value is given (at least one for a
  ///                semi-definite A, else the reduced system is singular)
  /// @param matrix  kSymmetric: A symmetric, A_ff positive definite; kGeneral: any A whose A_ff
  ///                is invertible (refactorize() then factorizes it anew)
  /// Throws SolverError if the reduced matrix cannot be factorized.
  DirichletSolver(const Eigen::SparseMatrix<double>& A, const std::vector<char>& fixed,
                  Matrix matrix = Matrix::kSymmetric);
  ~DirichletSolver();
  DirichletSolver(DirichletSolver&&) noexcept;
  DirichletSolver& operator=(DirichletSolver&&) noexcept;

  /// New values for A on the same sparsity pattern (same stored entries, in the same order) and
  /// the same fixed set: the values are copied into place and only the numeric factorization is
  /// redone, of the window only when the changed values stay in it. Throws InvalidInput if the
  /// pattern differs, SolverError as the constructor.
  /// @param focus  optional n flags: the rows later changes will be around (see
  ///                WindowedCholesky::refactorize); fixed rows are ignored
  void refactorize(const Eigen::SparseMatrix<double>& A, const std::vector<char>& focus = {});

  /// @param b        n x k right-hand sides (rows of fixed entries ignored)
  /// @param x_fixed  n x k values; only the rows of fixed entries are read
  /// @return n x k solution, fixed rows copied from x_fixed
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b, const Eigen::MatrixXd& x_fixed) const;

  int free_count() const { return int(free_.size()); }

 private:
  void split(const Eigen::SparseMatrix<double>& A);

  std::vector<int> free_;             // reduced index -> full index
  std::vector<int> reduced_;          // full index -> reduced index, or -1 if fixed
  Eigen::SparseMatrix<double> A_ff_;  // free x free block
  Eigen::SparseMatrix<double> A_fc_;  // free x all, fixed columns only
  // Per stored entry of A: its index in A_ff_'s values (>= 0), ~index in A_fc_'s (< 0 but not
  // kDropped), or kDropped for rows of fixed entries.
  static constexpr int kDropped = std::numeric_limits<int>::min();
  std::vector<int> destination_;
  Eigen::Index pattern_size_ = 0;
  // A_ff_'s factorization (null when every entry is fixed): Cholesky, or LU for kGeneral.
  std::unique_ptr<WindowedCholesky> cholesky_;
  struct LU;
  std::unique_ptr<LU> lu_;
};

}  // namespace geolens
