#pragma once
// Private: sparse Cholesky that refactorizes only the window of unknowns whose rows change.

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace geolens {

/// Solves A x = b for a symmetric positive definite sparse A (full symmetric storage) whose
/// values change between refactorizations only in a few rows, as the flattening matrix does
/// when a lens moves: only the rows of the triangles the lens lifts change.
///
/// With the unknowns split into the outside O and a window C (block elimination, O first):
///   A = [A_OO A_OC; A_CO A_CC],  A_OO = L L^T,  W = L^-1 A_OC,  M = A_CC - W^T W,
/// A_OO, A_OC and so L and W stay valid while every change is inside C x C, and refactorizing
/// is only M's numeric factorization (M is #C x #C: the window plus a dense block on its rim).
/// A first change refactorizes the whole matrix (a plain SimplicialLLT, analysis kept); a change
/// right after a full factorization, or one that leaves the window, builds a new window around
/// the focus rows (default: the rows changed since the previous call), dilated by `margin` times
/// their radius sqrt(#rows / pi) in rings of A's graph (at least 2), and factorizes everything
/// again.
class WindowedCholesky {
 public:
  /// @param A       n x n symmetric positive definite, both triangles stored
  /// @param margin  window dilation over the focus rows' radius, >= 0
  /// Throws SolverError if A is not positive definite, InvalidInput for bad arguments.
  explicit WindowedCholesky(const Eigen::SparseMatrix<double>& A, double margin = 0.25);
  ~WindowedCholesky();
  WindowedCholesky(WindowedCholesky&&) noexcept;
  WindowedCholesky& operator=(WindowedCholesky&&) noexcept;

  /// New values on the same pattern (same stored entries in the same order). Values are
  /// compared exactly, with the previous call's (which rows changed) and with the window's
  /// build (whether the change stays inside it): unchanged values must be bit-identical. Throws
  /// InvalidInput if the pattern differs, SolverError if the matrix is not positive definite.
  /// @param focus  optional n flags: the rows later changes will be around (for a lens, the
  ///                rows it lifts now); a new window is built around them instead of around
  ///                the rows that changed since the previous call (which, after a jump, hold
  ///                the old place too)
  void refactorize(const Eigen::SparseMatrix<double>& A, const std::vector<char>& focus = {});

  /// @param b  n x k right-hand sides
  /// @return n x k solutions
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;

  /// What the last refactorize() did.
  enum class Step {
    kNone,     ///< nothing changed (also the state after construction)
    kWindow,   ///< only the window block was refactorized
    kFull,     ///< the whole matrix was refactorized (first change, or no window worth it)
    kRebuild,  ///< a new window was built around the changed rows and factorized
  };
  Step last_step() const { return last_step_; }
  int window_size() const { return int(window_.size()); }  ///< #C, 0 without a window

 private:
  using SpMat = Eigen::SparseMatrix<double>;
  using LLT = Eigen::SimplicialLLT<SpMat>;  // with AMD ordering
  using OrderedLLT = Eigen::SimplicialLLT<SpMat, Eigen::Lower, Eigen::NaturalOrdering<int>>;
  void factorize_full(const SpMat& A);
  void build_window(const SpMat& A, const std::vector<char>& seed);
  // build_window()'s steps for the window's rows `inside` (n flags): window_ and outside_ in
  // order_, returning where the rim starts in window_; A's entries split into A_OO, A_OC and
  // the C x C triplets `cc` (with outside_entries_ and cc_entry_); M_'s pattern, schur_ and
  // cc_position_ from `cc` and Wt_.
  int split_unknowns(const SpMat& A, const std::vector<char>& inside);
  void split_entries(const SpMat& A, const std::vector<char>& inside, SpMat& A_oo, SpMat& A_oc,
                     std::vector<Eigen::Triplet<double>>& cc);
  void build_schur(const std::vector<Eigen::Triplet<double>>& cc, int rim_start);
  void factorize_window(const SpMat& A);

  double margin_;
  Eigen::Index n_ = 0;
  std::vector<double> reference_;  // A's values at the last full factorization or window build
  std::vector<double> previous_;   // A's values at the last call
  Step last_step_ = Step::kNone;

  // The whole matrix (used without a window); its AMD order orders the window's parts too.
  std::unique_ptr<LLT> full_;
  std::vector<int> order_;

  // With a window.
  std::vector<int> window_;            // C: window index -> row of A
  std::vector<int> outside_;           // O: outside index -> row of A
  std::vector<int> outside_entries_;   // stored entries of A outside C x C
  std::vector<int> cc_entry_;          // stored entries of A inside C x C ...
  std::vector<int> cc_position_;       // ... and their value index in M
  std::unique_ptr<OrderedLLT> outer_;  // A_OO = L L^T, O in order_
  SpMat W_;                            // L^-1 A_OC, #O x #C
  SpMat Wt_;                           // its transpose
  std::vector<double> schur_;          // -W^T W on M's pattern
  SpMat M_;
  std::unique_ptr<OrderedLLT> inner_;  // M, its rim last
};

}  // namespace geolens
