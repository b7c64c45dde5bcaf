#include "numerics/sparse_solver.h"

#include <Eigen/SparseLU>
#include <algorithm>
#include <string>

#include "geolens/core/errors.h"
#include "numerics/windowed_cholesky.h"

namespace geolens {

using SpMat = Eigen::SparseMatrix<double>;

struct DirichletSolver::LU {
  Eigen::SparseLU<SpMat> lu;
  void factorize(const SpMat& A_ff) {
    lu.compute(A_ff);
    if (lu.info() != Eigen::Success)
      throw SolverError("DirichletSolver: LU factorization failed on " +
                        std::to_string(A_ff.rows()) + " unknowns (singular)");
  }
};

DirichletSolver::DirichletSolver(const SpMat& A, const std::vector<char>& fixed, Matrix matrix) {
  require(A.rows() == A.cols() && size_t(A.rows()) == fixed.size(), "DirichletSolver",
          "matrix is " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) + " but " +
              std::to_string(fixed.size()) + " fixed flags were given");
  reduced_.assign(fixed.size(), -1);
  for (size_t i = 0; i < fixed.size(); ++i) {
    if (!fixed[i]) {
      reduced_[i] = int(free_.size());
      free_.push_back(int(i));
    }
  }
  split(A);
  if (free_.empty()) return;
  if (matrix == Matrix::kSymmetric) {
    cholesky_ = std::make_unique<WindowedCholesky>(A_ff_);
  } else {
    lu_ = std::make_unique<LU>();
    lu_->factorize(A_ff_);
  }
}

DirichletSolver::~DirichletSolver() = default;
DirichletSolver::DirichletSolver(DirichletSolver&&) noexcept = default;
DirichletSolver& DirichletSolver::operator=(DirichletSolver&&) noexcept = default;

void DirichletSolver::split(const SpMat& A) {
  const int nf = int(free_.size());
  std::vector<Eigen::Triplet<double>> ff, fc;
  ff.reserve(size_t(A.nonZeros()));
  for (int col = 0; col < A.outerSize(); ++col) {
    for (SpMat::InnerIterator it(A, col); it; ++it) {
      const int r = reduced_[size_t(it.row())];
      if (r < 0) continue;
      const int c = reduced_[size_t(it.col())];
      if (c >= 0) {
        ff.emplace_back(r, c, it.value());
      } else {
        fc.emplace_back(r, int(it.col()), it.value());
      }
    }
  }
  A_ff_.resize(nf, nf);
  A_ff_.setFromTriplets(ff.begin(), ff.end());
  A_fc_.resize(nf, A.cols());
  A_fc_.setFromTriplets(fc.begin(), fc.end());
  // Where each stored entry of A lands, so refactorize() only copies values.
  auto position = [](const SpMat& M, int row, int col) {
    const int* begin = M.innerIndexPtr() + M.outerIndexPtr()[col];
    const int* end = M.innerIndexPtr() + M.outerIndexPtr()[col + 1];
    return int(std::lower_bound(begin, end, row) - M.innerIndexPtr());
  };
  destination_.clear();
  destination_.reserve(size_t(A.nonZeros()));
  for (int col = 0; col < A.outerSize(); ++col) {
    for (SpMat::InnerIterator it(A, col); it; ++it) {
      const int r = reduced_[size_t(it.row())], c = reduced_[size_t(it.col())];
      if (r < 0) {
        destination_.push_back(kDropped);
      } else if (c >= 0) {
        destination_.push_back(position(A_ff_, r, c));
      } else {
        destination_.push_back(~position(A_fc_, r, int(it.col())));
      }
    }
  }
  pattern_size_ = A.nonZeros();
}

void DirichletSolver::refactorize(const SpMat& A, const std::vector<char>& focus) {
  require(focus.empty() || focus.size() == reduced_.size(), "DirichletSolver::refactorize",
          "focus must be empty or have one flag per row");
  require(
      size_t(A.rows()) == reduced_.size() && A.cols() == A.rows() && A.nonZeros() == pattern_size_,
      "DirichletSolver::refactorize", "the matrix must keep its size and sparsity pattern");
  const double* values = A.valuePtr();
  for (size_t k = 0; k < destination_.size(); ++k) {
    const int d = destination_[k];
    if (d == kDropped) continue;
    if (d >= 0) {
      A_ff_.valuePtr()[d] = values[k];
    } else {
      A_fc_.valuePtr()[~d] = values[k];
    }
  }
  if (free_.empty()) return;
  std::vector<char> focus_free;
  if (!focus.empty()) {
    focus_free.resize(free_.size());
    for (size_t r = 0; r < free_.size(); ++r) focus_free[r] = focus[size_t(free_[r])];
  }
  if (lu_) {
    lu_->factorize(A_ff_);
  } else {
    cholesky_->refactorize(A_ff_, focus_free);
  }
}

Eigen::MatrixXd DirichletSolver::solve(const Eigen::MatrixXd& b,
                                       const Eigen::MatrixXd& x_fixed) const {
  const Eigen::Index n = Eigen::Index(reduced_.size());
  require(b.rows() == n && x_fixed.rows() == n && b.cols() == x_fixed.cols(),
          "DirichletSolver::solve",
          "right-hand side and fixed values must have " + std::to_string(n) +
              " rows and equal columns");
  Eigen::MatrixXd x = x_fixed;
  if (free_.empty()) return x;
  Eigen::MatrixXd rhs(free_.size(), b.cols());
  for (size_t r = 0; r < free_.size(); ++r) rhs.row(Eigen::Index(r)) = b.row(free_[r]);
  rhs.noalias() -= A_fc_ * x_fixed;  // free rows of A_fc_ only touch fixed columns
  const Eigen::MatrixXd xf = lu_ ? Eigen::MatrixXd(lu_->lu.solve(rhs)) : cholesky_->solve(rhs);
  for (size_t r = 0; r < free_.size(); ++r) x.row(free_[r]) = xf.row(Eigen::Index(r));
  return x;
}

}  // namespace geolens
