#pragma once
// Private: flattening the lifted mesh back to the plane with the local/global solver (paper
// section 5); its options and result are public (lens_options.h).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geolens/core/solve_control.h"
#include "geolens/lens/lens_options.h"

namespace geolens {

class DirichletSolver;
class ThreadPool;  // core/thread_pool.h

/// Per-vertex constraints of focus lenses (LensModel::kFocus), which replace the metric target:
/// - a triangle whose three corners are in the focus of the same lens is asked to be its
///   (scaled) standard triangle exactly, translated but not rotated, with `focus_weight` times
///   its weight: the focus is magnified uniformly and keeps its orientation;
/// - any other triangle is asked to keep its shape distortion s1 / s2 at most the mean
///   `anisotropy` of its corners: its target is the closest matrix with that bound (the
///   projection of its singular values onto the cone s2 <= s1 <= K s2, after Lipman 2012's
///   bounded distortion maps), so the context may give way anisotropically, as it must;
/// - a pinned vertex stays where it is (beyond every footprint).
struct FocusConstraints {
  std::vector<int> focus;      ///< #V index of the lens whose focus holds the vertex, or -1
  std::vector<char> pinned;    ///< #V 1: the vertex keeps its position
  Eigen::VectorXd anisotropy;  ///< #V bound K >= 1 on s1 / s2 outside the foci
  double focus_weight = 1000;  ///< > 0
  bool empty() const { return focus.empty(); }
};

/// The local/global flattener of one lifted mesh. Construction computes the standard triangles
/// (each 3D triangle laid isometrically in the plane, paper Fig. 4, or the planar triangle
/// scaled, see Standard), the weights and the global matrix L; solve() then iterates, and
/// factorizes L by sparse Cholesky when it first takes a global step (factorize()).
///
/// Energy: E(X) = sum_t sum_{edges (i,j) of t} w_ij ||(x_i - x_j) - M_t (s_i - s_j)||^2
///              = sum_t c_t 2 A_t ||J_t - M_t||_F^2,
/// with s the standard triangle, J_t its Jacobian standard -> current, M_t the metric target,
/// w_ij = c_t cot(theta_ij) (c_t = 1 for kCotan weights). L is the weighted graph Laplacian
/// with the sign convention L_ii = sum_j w_ij > 0, L_ij = -w_ij (positive semidefinite,
/// L * 1 = 0).
class Flattener {
 public:
  /// @param V3     #V x 3 lifted vertices, pixels
  /// @param F      #F x 3 triangles
  /// @param level  #V normalized heights in [0, 1] (for the paper weights)
  /// @param sides  #V Side flags of the grid (border vertices), see grid.h
  /// @param log_scale  #V natural log of the magnification asked at each vertex (Standard::kScaled
  ///                   only; empty otherwise)
  /// @param focus  focus-lens constraints (empty: none, the metric applies everywhere)
  /// @param pool   the threads its loops run on, shared with the caller (GeometricLens passes
  ///               the lens's); null: a pool of its own of options.threads, started here and
  ///               kept for the flattener's life (across reweights and solves)
  Flattener(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F, const Eigen::VectorXd& level,
            const std::vector<uint8_t>& sides, const FlattenOptions& options,
            const Eigen::VectorXd& log_scale = Eigen::VectorXd(),
            const FocusConstraints& focus = {}, std::shared_ptr<ThreadPool> pool = nullptr);
  ~Flattener();

  /// Refits the flattener to a new lift of the same mesh (same faces, sides, options): the
  /// standard triangles and weights are recomputed, and the factorizations will be redone
  /// numerically on the kept symbolic analysis when a solve needs them. For a lens that moved.
  /// @param V3     #V x 3 lifted vertices, pixels (x, y also become the fixed values)
  /// @param level  #V normalized heights in [0, 1]
  /// @param log_scale  as in the constructor
  /// @param focus  as in the constructor, with the same pinned vertices
  void reweight(const Eigen::MatrixX3d& V3, const Eigen::VectorXd& level,
                const Eigen::VectorXd& log_scale = Eigen::VectorXd(),
                const FocusConstraints& focus = {});

  /// Iterates local and global steps from X0 (#V x 2; the paper starts from the projection of
  /// the 3D mesh) until the relative energy change is at most the tolerance or the cap.
  /// `guess` (optional, #V x 2) starts instead unless it folds a triangle. `control` (optional)
  /// hears of the start and of every step (SolveProgress::solve 0) and may stop the solve
  /// (Cancelled).
  FlattenResult solve(const Eigen::MatrixX2d& X0, const Eigen::MatrixX2d* guess = nullptr,
                      const SolveControl* control = nullptr) const;

  /// Brings the sparse Cholesky factorizations of the global step up to date with the weights:
  /// the analysis and factorization of L (x and y on two threads) the first time, the rows the
  /// reweights since changed after that. solve() calls it before its first global step; a start
  /// already at the minimum never needs it. Not safe to call from two threads at once (nor
  /// solve()).
  void factorize() const;

  /// Whether X (#V x 2) can start a flip-safe solve as it is: no triangle folded or degenerate,
  /// every fixed coordinate at its value.
  bool admissible(const Eigen::MatrixX2d& X) const;

  /// Focus constraints: raises each bounded triangle's anisotropy bound to its shape distortion
  /// s1 / s2 in X (#V x 2, admissible), so that X is feasible where the radial bounds are not
  /// (where lenses' rings overlap): the solve then only has to bring the foci to their shapes.
  void admit_anisotropy(const Eigen::MatrixX2d& X);

  /// E(X) with the metric targets fitted to X (the local step), see above.
  double energy(const Eigen::MatrixX2d& X) const;

  /// The global matrix L (#V x #V), before the boundary conditions.
  const Eigen::SparseMatrix<double>& laplacian() const;

 private:
  struct Triangle {
    Eigen::Matrix2d S_inv;  // inverse of the standard edge matrix [s1 - s0, s2 - s0]
    Eigen::Matrix2d S;      // the standard edge matrix
    double area2c;          // 2 A_t c_t: the triangle's weight in ||J - M||_F^2
    Eigen::Vector3d w;      // w for the edge opposite each corner
    // Focus constraints: the target is the identity (kFocus), or J with s1 / s2 bounded by
    // `anisotropy` (kBounded), or the metric's (kMetric).
    enum Kind : uint8_t { kMetric, kFocus, kBounded } kind = kMetric;
    double anisotropy = 1;
  };
  void assemble(const Eigen::MatrixX3d& V3, const Eigen::VectorXd& level,
                const Eigen::VectorXd& log_scale, const FocusConstraints& focus);
  // assemble()'s steps: each triangle's standard triangle (S, its inverse and 2 A, `scaled` or
  // the lift laid flat), returning the triangles' planar areas (#F); then their weights c_t
  // (into area2c), kinds and edge weights w.
  std::vector<double> lay_standard_triangles(const Eigen::MatrixX3d& V3,
                                             const Eigen::VectorXd& log_scale, bool scaled);
  void weigh_triangles(const Eigen::VectorXd& level, const FocusConstraints& focus,
                       double mean_area);
  // L_ from the triangles' weights, if assemble() changed them since (the first time, its
  // pattern too): only a factorization needs it.
  void update_laplacian() const;
  Eigen::Matrix2d target(const Eigen::Matrix2d& J) const;
  Eigen::Matrix2d target(const Triangle& t, const Eigen::Matrix2d& J) const;
  // Whether every fixed coordinate of X (#V x 2) has its value in `values` (#V x 2).
  bool keeps_fixed(const Eigen::MatrixX2d& X, const Eigen::MatrixXd& values) const;
  // The largest step s in (0, 1] from X toward `next` that keeps every triangle's orientation.
  double max_orientation_step(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& next) const;
  Eigen::Matrix2d jacobian(const Triangle& t, int f, const Eigen::MatrixX2d& X) const;
  // The local step's results per triangle: its corners' shares (3 f + k) of the global step's
  // right-hand side (for each edge (a, c) of weight w, w M (s_a - s_c) to a, its negative to
  // c), its energy and whether it is folded.
  struct LocalFit {
    explicit LocalFit(size_t triangles)
        : share(triangles * 3), energy(triangles), folded(triangles) {}
    std::vector<Eigen::Vector2d> share;
    std::vector<double> energy;
    std::vector<char> folded;
  };
  // The local step at X (#V x 2): each triangle's target fitted, into `fit`; returns E(X).
  double local_step(const Eigen::MatrixX2d& X, LocalFit& fit) const;
  // The energy below which a solve has converged (the exact solution up to rounding, or the
  // bounded triangles within the tolerance of feasible).
  double negligible_energy() const;
  // The global step's right-hand side (#V x 2): the corners' shares summed per vertex.
  Eigen::MatrixXd right_hand_side(const std::vector<Eigen::Vector2d>& share) const;
  // The global step's solution (#V x 2) for right-hand side b, fixed coordinates at
  // `fixed_values` (#V x 2); factorizes first if needed.
  Eigen::MatrixX2d global_step(const Eigen::MatrixXd& b, const Eigen::MatrixXd& fixed_values) const;

  std::shared_ptr<ThreadPool> pool_;
  Eigen::MatrixX3i F_;
  Eigen::MatrixX2d rest_;  // the grid's 2D positions: the values of fixed coordinates
  FlattenOptions options_;
  std::vector<Triangle> triangles_;
  mutable Eigen::SparseMatrix<double> L_;
  mutable std::vector<int> entry_position_;  // value index in L_ of each assembled entry
  mutable bool laplacian_stale_ = true;      // L_ lags the triangles' weights
  // The corners (3 f + k) at each vertex v: corner_[corner_start_[v] .. corner_start_[v + 1]).
  std::vector<int> corner_start_, corner_;
  std::vector<char> fix_x_, fix_y_;  // #V: the coordinate keeps its fixed value
  // One solver for both coordinates, or (sliding) one per coordinate, factorized on the first
  // global step a solve takes (factorize()), so a start already at the minimum costs none;
  // `changed_` holds the rows reweighted since (empty: none).
  mutable std::unique_ptr<DirichletSolver> solver_x_, solver_y_;
  mutable std::vector<char> changed_;
};

/// One-off: builds a Flattener and solves from the projection of V3.
FlattenResult flatten(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                      const Eigen::VectorXd& level, const std::vector<uint8_t>& sides,
                      const FlattenOptions& options,
                      const Eigen::VectorXd& log_scale = Eigen::VectorXd());

}  // namespace geolens
