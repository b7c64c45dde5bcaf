#include "numerics/windowed_cholesky.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

// The window is not worth it when it would hold more than this share of the unknowns.
constexpr double kMaxWindowShare = 0.6;

template <typename Solver>
void check_factorization(const Solver& llt, Eigen::Index n) {
  if (llt.info() != Eigen::Success)
    throw SolverError("WindowedCholesky: Cholesky factorization failed on a " + std::to_string(n) +
                      "-unknown system (not positive definite)");
}

// L^-1 B for a sparse lower-triangular L (diagonal stored first in each column) and a sparse B,
// solved over the reach of B's non-zero rows only: their elimination-tree ancestors (Gilbert's
// theorem), so the cost follows the result, not the size of L. Columns go in blocks of kBlock
// that share one pass over their reaches' union (the ancestors near the root are common).
SpMat lower_solve(const SpMat& L, const SpMat& B) {
  constexpr int kBlock = 8;
  const Eigen::Index n = L.rows();
  std::vector<int> parent(size_t(n), -1);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index first = L.outerIndexPtr()[j];
    if (first + 1 < L.outerIndexPtr()[j + 1]) parent[size_t(j)] = L.innerIndexPtr()[first + 1];
  }
  std::vector<double> y(size_t(n) * kBlock, 0.0);  // row-major n x kBlock
  std::vector<Eigen::Index> mark(size_t(n), -1);
  std::vector<int> reach;
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index c0 = 0; c0 < B.cols(); c0 += kBlock) {
    const int width = int(std::min<Eigen::Index>(kBlock, B.cols() - c0));
    reach.clear();
    for (int b = 0; b < width; ++b) {
      for (SpMat::InnerIterator it(B, c0 + b); it; ++it) {
        y[size_t(it.row()) * kBlock + size_t(b)] = it.value();
        for (int i = int(it.row()); i >= 0 && mark[size_t(i)] != c0; i = parent[size_t(i)]) {
          mark[size_t(i)] = c0;
          reach.push_back(i);
        }
      }
    }
    std::sort(reach.begin(), reach.end());
    for (const int j : reach) {
      const Eigen::Index begin = L.outerIndexPtr()[j], end = L.outerIndexPtr()[j + 1];
      double* yj = &y[size_t(j) * kBlock];
      const double inverse = 1.0 / L.valuePtr()[begin];
      for (int b = 0; b < kBlock; ++b) yj[b] *= inverse;
      for (Eigen::Index k = begin + 1; k < end; ++k) {
        double* yi = &y[size_t(L.innerIndexPtr()[k]) * kBlock];
        const double l = L.valuePtr()[k];
        for (int b = 0; b < kBlock; ++b) yi[b] -= l * yj[b];
      }
      for (int b = 0; b < width; ++b)
        if (yj[b] != 0) entries.emplace_back(j, int(c0) + b, yj[b]);
      std::fill(yj, yj + kBlock, 0.0);
    }
  }
  SpMat X(n, B.cols());
  X.setFromTriplets(entries.begin(), entries.end());
  return X;
}

// The seed rows (n flags) dilated by whole rings of A's graph, `margin` times their radius
// sqrt(#rows / pi) and at least 2: n flags, or none if the seed is empty or the window would
// hold more than kMaxWindowShare of the unknowns.
std::vector<char> window_rows(const SpMat& A, const std::vector<char>& seed, double margin) {
  const Eigen::Index n = A.rows();
  std::vector<int> frontier;
  for (Eigen::Index i = 0; i < n; ++i)
    if (seed[size_t(i)]) frontier.push_back(int(i));
  if (frontier.empty()) return {};
  const double radius = std::sqrt(double(frontier.size()) / M_PI);
  const int rings = std::max(2, int(std::ceil(margin * radius)));
  std::vector<char> inside = seed;
  size_t count = frontier.size();
  for (int ring = 0; ring < rings && !frontier.empty(); ++ring) {
    std::vector<int> next;
    for (const int col : frontier) {
      for (Eigen::Index k = A.outerIndexPtr()[col]; k < A.outerIndexPtr()[col + 1]; ++k) {
        const int row = A.innerIndexPtr()[k];
        if (!inside[size_t(row)]) {
          inside[size_t(row)] = 1;
          next.push_back(row);
        }
      }
    }
    count += next.size();
    frontier.swap(next);
  }
  if (double(count) > kMaxWindowShare * double(n)) return {};
  return inside;
}

// S = W^T W (nr x nr), given Wt = W^T: it lives on the rim x rim block (only the rim columns of
// W, from rim_start, are non-zero), summed densely over the rows of W.
Eigen::MatrixXd rim_gram(const SpMat& Wt, int rim_start, int nr) {
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(nr, nr);
  for (Eigen::Index o = 0; o < Wt.outerSize(); ++o) {
    const Eigen::Index begin = Wt.outerIndexPtr()[o], end = Wt.outerIndexPtr()[o + 1];
    for (Eigen::Index a = begin; a < end; ++a) {
      const int ca = Wt.innerIndexPtr()[a] - rim_start;
      const double va = Wt.valuePtr()[a];
      for (Eigen::Index b = begin; b < end; ++b)
        S(Wt.innerIndexPtr()[b] - rim_start, ca) += va * Wt.valuePtr()[b];
    }
  }
  return S;
}

}  // namespace

WindowedCholesky::WindowedCholesky(const SpMat& A, double margin) : margin_(margin) {
  require(A.rows() == A.cols() && A.rows() > 0, "WindowedCholesky",
          "the matrix must be square and non-empty, got " + std::to_string(A.rows()) + "x" +
              std::to_string(A.cols()));
  require(std::isfinite(margin) && margin >= 0, "WindowedCholesky",
          "margin must be finite and >= 0, got " + std::to_string(margin));
  require(A.isCompressed(), "WindowedCholesky", "the matrix must be compressed");
  n_ = A.rows();
  factorize_full(A);
  previous_ = reference_;
}

WindowedCholesky::~WindowedCholesky() = default;
WindowedCholesky::WindowedCholesky(WindowedCholesky&&) noexcept = default;
WindowedCholesky& WindowedCholesky::operator=(WindowedCholesky&&) noexcept = default;

void WindowedCholesky::factorize_full(const SpMat& A) {
  window_.clear();
  outside_.clear();
  outer_.reset();
  inner_.reset();
  if (!full_) {
    full_ = std::make_unique<LLT>();
    full_->analyzePattern(A);
    // The elimination order AMD chose: row order_[k] is eliminated k-th.
    order_.resize(size_t(n_));
    const auto& position = full_->permutationP().indices();
    for (Eigen::Index i = 0; i < n_; ++i) order_[size_t(position(i))] = int(i);
  }
  full_->factorize(A);
  check_factorization(*full_, n_);
  reference_.assign(A.valuePtr(), A.valuePtr() + A.nonZeros());
}

void WindowedCholesky::refactorize(const SpMat& A, const std::vector<char>& focus) {
  require(A.rows() == n_ && A.cols() == n_ && A.isCompressed() &&
              A.nonZeros() == Eigen::Index(reference_.size()),
          "WindowedCholesky::refactorize", "the matrix must keep its size and sparsity pattern");
  require(focus.empty() || focus.size() == size_t(n_), "WindowedCholesky::refactorize",
          "focus must be empty or have one flag per row");
  const double* values = A.valuePtr();
  // Rows whose entries changed since the previous call: the seed of a new window.
  std::vector<char> changed(size_t(n_), 0);
  bool any = false;
  for (Eigen::Index col = 0; col < n_; ++col) {
    for (Eigen::Index k = A.outerIndexPtr()[col]; k < A.outerIndexPtr()[col + 1]; ++k) {
      if (values[k] != previous_[size_t(k)]) {
        changed[size_t(col)] = changed[size_t(A.innerIndexPtr()[k])] = 1;
        any = true;
      }
    }
  }
  previous_.assign(values, values + A.nonZeros());
  if (!any) {
    last_step_ = Step::kNone;
    return;
  }
  if (!window_.empty()) {
    const bool inside = std::all_of(outside_entries_.begin(), outside_entries_.end(),
                                    [&](int k) { return values[k] == reference_[size_t(k)]; });
    if (inside) {
      factorize_window(A);
      last_step_ = Step::kWindow;
    } else {
      build_window(A, focus.empty() ? changed : focus);
    }
  } else if (last_step_ == Step::kFull) {
    // Changing again right after a full factorization: worth a window (a one-off change, such
    // as a new lift of a fixed lens, is cheaper refactorized whole).
    build_window(A, focus.empty() ? changed : focus);
  } else {
    factorize_full(A);
    last_step_ = Step::kFull;
  }
}

void WindowedCholesky::build_window(const SpMat& A, const std::vector<char>& seed) {
  // The window's rows: the seed dilated; none if that is empty or no window is worth it.
  const std::vector<char> inside = window_rows(A, seed, margin_);
  if (inside.empty()) {
    factorize_full(A);
    last_step_ = Step::kFull;
    return;
  }
  last_step_ = Step::kRebuild;
  // The unknowns split into O and C, its rim last, and A's entries into their blocks.
  const int rim_start = split_unknowns(A, inside);
  const int no = int(outside_.size()), nc = int(window_.size());
  SpMat A_oo(no, no), A_oc(no, nc);
  std::vector<Eigen::Triplet<double>> cc;
  split_entries(A, inside, A_oo, A_oc, cc);
  // A_OO = L L^T and W = L^-1 A_OC.
  outer_ = std::make_unique<OrderedLLT>(A_oo);
  check_factorization(*outer_, no);
  W_ = lower_solve(outer_->matrixL().nestedExpression(), A_oc);
  Wt_ = W_.transpose();
  // M's pattern and the part of its values that stays (-W^T W), analyzed and factorized.
  build_schur(cc, rim_start);
  inner_ = std::make_unique<OrderedLLT>();
  inner_->analyzePattern(M_);
  factorize_window(A);
  reference_.assign(A.valuePtr(), A.valuePtr() + A.nonZeros());
}

int WindowedCholesky::split_unknowns(const SpMat& A, const std::vector<char>& inside) {
  // Each part in the whole matrix's fill-reducing elimination order (so no new ordering is
  // computed): O; then C, the rows of C next to O (the rim, where M is dense) last.
  std::vector<char> rim(size_t(n_), 0);
  for (Eigen::Index col = 0; col < n_; ++col) {
    if (inside[size_t(col)]) continue;
    for (Eigen::Index k = A.outerIndexPtr()[col]; k < A.outerIndexPtr()[col + 1]; ++k)
      rim[size_t(A.innerIndexPtr()[k])] = inside[size_t(A.innerIndexPtr()[k])];
  }
  window_.clear();
  outside_.clear();
  std::vector<int> rim_rows;
  for (const int i : order_) {
    if (!inside[size_t(i)]) {
      outside_.push_back(i);
    } else if (rim[size_t(i)]) {
      rim_rows.push_back(i);
    } else {
      window_.push_back(i);
    }
  }
  const int rim_start = int(window_.size());
  window_.insert(window_.end(), rim_rows.begin(), rim_rows.end());
  return rim_start;
}

void WindowedCholesky::split_entries(const SpMat& A, const std::vector<char>& inside, SpMat& A_oo,
                                     SpMat& A_oc, std::vector<Eigen::Triplet<double>>& cc) {
  std::vector<int> local(static_cast<size_t>(n_));
  for (size_t i = 0; i < outside_.size(); ++i) local[size_t(outside_[i])] = int(i);
  for (size_t i = 0; i < window_.size(); ++i) local[size_t(window_[i])] = int(i);
  std::vector<Eigen::Triplet<double>> oo, oc;
  outside_entries_.clear();
  cc_entry_.clear();
  const double* values = A.valuePtr();
  for (Eigen::Index col = 0; col < n_; ++col) {
    for (Eigen::Index k = A.outerIndexPtr()[col]; k < A.outerIndexPtr()[col + 1]; ++k) {
      const int row = A.innerIndexPtr()[k];
      const int r = local[size_t(row)], c = local[size_t(col)];
      const bool row_in = inside[size_t(row)], col_in = inside[size_t(col)];
      if (row_in && col_in) {
        cc.emplace_back(r, c, values[k]);
        cc_entry_.push_back(int(k));
        continue;
      }
      outside_entries_.push_back(int(k));
      if (!row_in && !col_in) {
        oo.emplace_back(r, c, values[k]);
      } else if (!row_in) {
        oc.emplace_back(r, c, values[k]);
      }
    }
  }
  A_oo.setFromTriplets(oo.begin(), oo.end());
  A_oc.setFromTriplets(oc.begin(), oc.end());
}

void WindowedCholesky::build_schur(const std::vector<Eigen::Triplet<double>>& cc, int rim_start) {
  // M = A_CC - S; schur_ keeps -S on M's pattern, the part that stays.
  const int nc = int(window_.size()), nr = nc - rim_start;
  const Eigen::MatrixXd S = rim_gram(Wt_, rim_start, nr);
  std::vector<Eigen::Triplet<double>> m = cc;
  m.reserve(cc.size() + size_t(nr) * size_t(nr));
  for (int c = 0; c < nr; ++c)
    for (int r = 0; r < nr; ++r) m.emplace_back(rim_start + r, rim_start + c, -S(r, c));
  M_.resize(nc, nc);
  M_.setFromTriplets(m.begin(), m.end());
  schur_.assign(M_.valuePtr(), M_.valuePtr() + M_.nonZeros());
  cc_position_.resize(cc_entry_.size());
  for (size_t e = 0; e < cc_entry_.size(); ++e) {
    const int r = cc[e].row(), c = cc[e].col();
    const int* begin = M_.innerIndexPtr() + M_.outerIndexPtr()[c];
    const int* end = M_.innerIndexPtr() + M_.outerIndexPtr()[c + 1];
    cc_position_[e] = int(std::lower_bound(begin, end, r) - M_.innerIndexPtr());
    schur_[size_t(cc_position_[e])] -= cc[e].value();
  }
}

void WindowedCholesky::factorize_window(const SpMat& A) {
  std::copy(schur_.begin(), schur_.end(), M_.valuePtr());
  for (size_t e = 0; e < cc_entry_.size(); ++e)
    M_.valuePtr()[cc_position_[e]] += A.valuePtr()[cc_entry_[e]];
  inner_->factorize(M_);
  check_factorization(*inner_, M_.rows());
}

Eigen::MatrixXd WindowedCholesky::solve(const Eigen::MatrixXd& b) const {
  require(
      b.rows() == n_, "WindowedCholesky::solve",
      "right-hand side has " + std::to_string(b.rows()) + " rows, expected " + std::to_string(n_));
  if (window_.empty()) return full_->solve(b);
  const Eigen::Index k = b.cols();
  Eigen::MatrixXd b_o(outside_.size(), k), b_c(window_.size(), k);
  for (size_t i = 0; i < outside_.size(); ++i) b_o.row(Eigen::Index(i)) = b.row(outside_[i]);
  for (size_t i = 0; i < window_.size(); ++i) b_c.row(Eigen::Index(i)) = b.row(window_[i]);
  // y = L^-1 b_O;  x_C = M^-1 (b_C - W^T y);  x_O = L^-T (y - W x_C).
  Eigen::MatrixXd& y = b_o;
  outer_->matrixL().solveInPlace(y);
  b_c.noalias() -= Wt_ * y;
  const Eigen::MatrixXd x_c = inner_->solve(b_c);
  y.noalias() -= W_ * x_c;
  outer_->matrixU().solveInPlace(y);
  Eigen::MatrixXd x(n_, k);
  for (size_t i = 0; i < outside_.size(); ++i) x.row(outside_[i]) = y.row(Eigen::Index(i));
  for (size_t i = 0; i < window_.size(); ++i) x.row(window_[i]) = x_c.row(Eigen::Index(i));
  return x;
}

}  // namespace geolens
