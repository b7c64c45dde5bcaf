#include "lens/flatten.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>

#include "core/parallel.h"
#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"
#include "lens/texture_map.h"
#include "numerics/sparse_solver.h"
#include "numerics/svd2.h"

namespace geolens {

Flattener::Flattener(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                     const Eigen::VectorXd& level, const std::vector<uint8_t>& sides,
                     const FlattenOptions& options, const Eigen::VectorXd& log_scale,
                     const FocusConstraints& focus, std::shared_ptr<ThreadPool> pool)
    : F_(F), rest_(V3.leftCols<2>()), options_(options) {
  validate(options);
  pool_ = pool ? std::move(pool) : std::make_shared<ThreadPool>(options.threads);
  const Eigen::Index n = V3.rows();
  require(sides.size() == size_t(n), "Flattener", "sides must have one entry per vertex");
  require(F.rows() > 0 && F.minCoeff() >= 0 && F.maxCoeff() < n, "Flattener",
          "faces must index the " + std::to_string(n) + " vertices");
  corner_start_.assign(size_t(n) + 1, 0);
  for (Eigen::Index k = 0; k < F.size(); ++k) ++corner_start_[size_t(F(k / 3, k % 3)) + 1];
  for (size_t v = 0; v < size_t(n); ++v) corner_start_[v + 1] += corner_start_[v];
  corner_.resize(size_t(F.size()));
  std::vector<int> fill(corner_start_.begin(), corner_start_.end() - 1);
  for (Eigen::Index k = 0; k < F.size(); ++k)
    corner_[size_t(fill[size_t(F(k / 3, k % 3))]++)] = int(k);
  assemble(V3, level, log_scale, focus);

  std::vector<char> fix_x(size_t(n), 0), fix_y(size_t(n), 0);
  for (size_t i = 0; i < size_t(n); ++i) {
    switch (options.boundary) {
      case Boundary::kSliding:
        fix_x[i] = (sides[i] & (kLeft | kRight)) != 0;
        fix_y[i] = (sides[i] & (kTop | kBottom)) != 0;
        break;
      case Boundary::kFixed:
        fix_x[i] = fix_y[i] = sides[i] != 0;
        break;
      case Boundary::kFree:
        break;
    }
  }
  if (options.boundary == Boundary::kFree) fix_x[0] = fix_y[0] = 1;
  for (size_t i = 0; i < focus.pinned.size(); ++i)
    if (focus.pinned[i]) fix_x[i] = fix_y[i] = 1;
  require(std::find(fix_x.begin(), fix_x.end(), 1) != fix_x.end() &&
              std::find(fix_y.begin(), fix_y.end(), 1) != fix_y.end(),
          "Flattener", "the boundary mode fixes no vertex: are the grid sides set?");
  fix_x_ = std::move(fix_x);
  fix_y_ = std::move(fix_y);
}

void Flattener::factorize() const {
  update_laplacian();
  if (!solver_x_) {
    // Both or neither: a y system that fails after x was built must not leave x alone, which
    // later solves would take for both coordinates.
    std::unique_ptr<DirichletSolver> x, y;
    if (fix_x_ == fix_y_) {
      x = std::make_unique<DirichletSolver>(L_, fix_x_);
    } else {
      parallel_invoke(
          *pool_, [&] { x = std::make_unique<DirichletSolver>(L_, fix_x_); },
          [&] { y = std::make_unique<DirichletSolver>(L_, fix_y_); });
    }
    solver_x_ = std::move(x);
    solver_y_ = std::move(y);
    changed_.clear();
    return;
  }
  if (changed_.empty()) return;
  if (solver_y_) {
    parallel_invoke(
        *pool_, [&] { solver_x_->refactorize(L_, changed_); },
        [&] { solver_y_->refactorize(L_, changed_); });
  } else {
    solver_x_->refactorize(L_, changed_);
  }
  changed_.clear();
}

void Flattener::reweight(const Eigen::MatrixX3d& V3, const Eigen::VectorXd& level,
                         const Eigen::VectorXd& log_scale, const FocusConstraints& focus) {
  require(V3.rows() == rest_.rows(), "Flattener::reweight",
          "the lifted mesh has " + std::to_string(V3.rows()) + " vertices, expected " +
              std::to_string(rest_.rows()));
  rest_ = V3.leftCols<2>();
  assemble(V3, level, log_scale, focus);
  if (!solver_x_) return;  // not factorized yet: factorize() will start from this L
  // The rows the lift touches (a triangle with a lifted corner changes all three): where the
  // next lift's changes will be, for the factorizations' windows. Added to those of the
  // reweights since the last factorization.
  changed_.resize(size_t(V3.rows()), 0);
  for (Eigen::Index f = 0; f < F_.rows(); ++f) {
    if (level(F_(f, 0)) > 0 || level(F_(f, 1)) > 0 || level(F_(f, 2)) > 0)
      changed_[size_t(F_(f, 0))] = changed_[size_t(F_(f, 1))] = changed_[size_t(F_(f, 2))] = 1;
  }
}

std::vector<double> Flattener::lay_standard_triangles(const Eigen::MatrixX3d& V3,
                                                      const Eigen::VectorXd& log_scale,
                                                      bool scaled) {
  triangles_.resize(size_t(F_.rows()));
  std::vector<double> planar_area(triangles_.size());
  std::vector<char> degenerate(triangles_.size(), 0);
  parallel_for(*pool_, triangles_.size(), [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f) {
      const Eigen::Index fi = Eigen::Index(f);
      const Eigen::Vector3d e1 = V3.row(F_(fi, 1)) - V3.row(F_(fi, 0));
      const Eigen::Vector3d e2 = V3.row(F_(fi, 2)) - V3.row(F_(fi, 0));
      const double l1 = e1.norm(), cross = e1.cross(e2).norm();
      const double planar_cross = e1.x() * e2.y() - e1.y() * e2.x();
      if (!(l1 > 0 && cross > 0) || (scaled && !(planar_cross > 0))) {
        degenerate[f] = 1;
        continue;
      }
      Triangle& t = triangles_[f];
      if (scaled) {
        const double s =
            std::exp((log_scale(F_(fi, 0)) + log_scale(F_(fi, 1)) + log_scale(F_(fi, 2))) / 3.0);
        t.S << e1.x(), e2.x(), e1.y(), e2.y();
        t.S *= s;
        t.area2c = s * s * planar_cross;  // 2 A, times c_t below
      } else {
        t.S << l1, e1.dot(e2) / l1, 0, cross / l1;
        t.area2c = cross;
      }
      t.S_inv = t.S.inverse();
      planar_area[f] = 0.5 * std::abs(planar_cross);
    }
  });
  const auto bad = std::find(degenerate.begin(), degenerate.end(), 1);
  require(bad == degenerate.end(), "Flattener",
          "triangle " + std::to_string(bad - degenerate.begin()) +
              (scaled ? " is degenerate or clockwise in the plane" : " is degenerate in 3D"));
  return planar_area;
}

void Flattener::weigh_triangles(const Eigen::VectorXd& level, const FocusConstraints& focus,
                                double mean_area) {
  parallel_for(*pool_, triangles_.size(), [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f) {
      Triangle& t = triangles_[f];
      const Eigen::Index fi = Eigen::Index(f);
      double c = 1.0;
      if (options_.weights == FlattenWeights::kPaper) {
        const double h = (level(F_(fi, 0)) + level(F_(fi, 1)) + level(F_(fi, 2))) / 3.0;
        c = (1.0 + h) * (0.5 * t.area2c) / mean_area;
      }
      t.kind = Triangle::kMetric;
      if (!focus.empty()) {
        const int a = focus.focus[size_t(F_(fi, 0))];
        if (a >= 0 && focus.focus[size_t(F_(fi, 1))] == a && focus.focus[size_t(F_(fi, 2))] == a) {
          t.kind = Triangle::kFocus;
          c *= focus.focus_weight;
        } else {
          t.kind = Triangle::kBounded;
          t.anisotropy = (focus.anisotropy(F_(fi, 0)) + focus.anisotropy(F_(fi, 1)) +
                          focus.anisotropy(F_(fi, 2))) /
                         3.0;
        }
      }
      t.area2c *= c;
      const Eigen::Vector2d s[3] = {Eigen::Vector2d::Zero(), t.S.col(0), t.S.col(1)};
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d a = s[(k + 1) % 3] - s[k], b = s[(k + 2) % 3] - s[k];
        t.w(k) = c * a.dot(b) / std::abs(a.x() * b.y() - a.y() * b.x());
      }
    }
  });
}

void Flattener::assemble(const Eigen::MatrixX3d& V3, const Eigen::VectorXd& level,
                         const Eigen::VectorXd& log_scale, const FocusConstraints& focus) {
  const Eigen::Index n = V3.rows();
  require(level.size() == n, "Flattener", "level must have one entry per vertex");
  require(focus.empty() || (focus.focus.size() == size_t(n) && focus.pinned.size() == size_t(n) &&
                            focus.anisotropy.size() == n && focus.anisotropy.minCoeff() >= 1 &&
                            std::isfinite(focus.focus_weight) && focus.focus_weight > 0),
          "Flattener",
          "focus constraints need one focus, pin and anisotropy bound >= 1 per vertex and a "
          "positive focus weight");
  const bool scaled = options_.standard == Standard::kScaled;
  require(!scaled || (log_scale.size() == n && log_scale.allFinite()), "Flattener",
          "scaled standard triangles need one finite log scale per vertex");
  // Standard triangles: the lifted triangle laid flat (paper Fig. 4: v0 at the origin, v1 on the
  // x axis, v2 above), or the planar triangle scaled.
  const std::vector<double> planar_area = lay_standard_triangles(V3, log_scale, scaled);
  // The paper weights' area normalization: any constant scales E without moving its minimum;
  // the planar mean keeps the weights of unlifted triangles bit-identical from lift to lift,
  // so a moved lens changes only the rows it lifts (WindowedCholesky relies on it).
  const double mean_area =
      std::accumulate(planar_area.begin(), planar_area.end(), 0.0) / double(triangles_.size());
  // Each triangle's weight, kind (focus constraints) and edge weights.
  weigh_triangles(level, focus, mean_area);
  laplacian_stale_ = true;  // L_ follows when a factorization needs it
}

const Eigen::SparseMatrix<double>& Flattener::laplacian() const {
  update_laplacian();
  return L_;
}

void Flattener::update_laplacian() const {
  if (!laplacian_stale_) return;
  laplacian_stale_ = false;
  const Eigen::Index n = rest_.rows();
  // L = sum over triangles and their edges (i, j) of w (e_i - e_j)(e_i - e_j)^T, entries in a
  // fixed order (so the sums, too, are the same from one assembly to the next): the pattern is
  // built once, later assemblies add the values into place.
  if (L_.rows() != n) {
    // The pattern column by column: each vertex and its neighbours, sorted (a column holds about
    // seven, so this is several times faster than sorting triplets).
    std::vector<int> outer(size_t(n) + 1, 0);
    for (Eigen::Index f = 0; f < F_.rows(); ++f)
      for (int k = 0; k < 3; ++k) outer[size_t(F_(f, k)) + 1] += 3;
    std::partial_sum(outer.begin(), outer.end(), outer.begin());
    std::vector<int> inner(size_t(outer.back())), fill(outer.begin(), outer.end() - 1);
    for (Eigen::Index f = 0; f < F_.rows(); ++f)
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) inner[size_t(fill[size_t(F_(f, k))]++)] = F_(f, (k + j) % 3);
    int nonzeros = 0;
    for (Eigen::Index c = 0; c < n; ++c) {
      const auto begin = inner.begin() + outer[size_t(c)],
                 end = inner.begin() + outer[size_t(c) + 1];
      std::sort(begin, end);
      const auto last = std::unique(begin, end);
      outer[size_t(c)] = nonzeros;
      nonzeros = int(std::copy(begin, last, inner.begin() + nonzeros) - inner.begin());
    }
    outer[size_t(n)] = nonzeros;
    const std::vector<double> zeros(size_t(nonzeros), 0.0);
    L_ = Eigen::Map<const Eigen::SparseMatrix<double>>(n, n, nonzeros, outer.data(), inner.data(),
                                                       zeros.data());
    auto at = [&](int row, int col) {
      const int* begin = L_.innerIndexPtr() + L_.outerIndexPtr()[col];
      const int* end = L_.innerIndexPtr() + L_.outerIndexPtr()[col + 1];
      return int(std::lower_bound(begin, end, row) - L_.innerIndexPtr());
    };
    entry_position_.clear();
    entry_position_.reserve(triangles_.size() * 12);
    for (Eigen::Index f = 0; f < F_.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int i = F_(f, (k + 1) % 3), j = F_(f, (k + 2) % 3);
        for (const int position : {at(i, i), at(j, j), at(i, j), at(j, i)})
          entry_position_.push_back(position);
      }
    }
  }
  double* values = L_.valuePtr();
  std::fill(values, values + L_.nonZeros(), 0.0);
  const int* position = entry_position_.data();
  for (const Triangle& t : triangles_) {
    for (int k = 0; k < 3; ++k, position += 4) {
      values[position[0]] += t.w(k);
      values[position[1]] += t.w(k);
      values[position[2]] -= t.w(k);
      values[position[3]] -= t.w(k);
    }
  }
}

Flattener::~Flattener() = default;

inline Eigen::Matrix2d Flattener::jacobian(const Triangle& t, int f,
                                           const Eigen::MatrixX2d& X) const {
  Eigen::Matrix2d E;
  E.col(0) = (X.row(F_(f, 1)) - X.row(F_(f, 0))).transpose();
  E.col(1) = (X.row(F_(f, 2)) - X.row(F_(f, 0))).transpose();
  return E * t.S_inv;
}

inline Eigen::Matrix2d Flattener::target(const Eigen::Matrix2d& J) const {
  // With J = U diag(s1, s2) V^T (signed SVD), the closest rotation R = U V^T is [E -H; H E] / Q
  // for E = (J00 + J11) / 2, H = (J10 - J01) / 2, Q = |(E, H)| = (s1 + s2) / 2 (svd2.cpp), so
  // no SVD is needed: the paper's U diag(alpha (s - 1) + 1) V^T is (1 - alpha) R + alpha J, and
  // the spectrum's target is ((1 - alpha) + alpha Q) R.
  const double E = 0.5 * (J(0, 0) + J(1, 1)), H = 0.5 * (J(1, 0) - J(0, 1));
  const double Q = std::sqrt(E * E + H * H);  // no overflow at pixel scales; hypot is slow
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
  if (Q > 0) R << E / Q, -H / Q, H / Q, E / Q;
  const double a = options_.alpha;
  if (options_.metric == Metric::kPaper) return (1 - a) * R + a * J;
  return ((1 - a) + a * Q) * R;
}

inline Eigen::Matrix2d Flattener::target(const Triangle& t, const Eigen::Matrix2d& J) const {
  switch (t.kind) {
    case Triangle::kMetric:
      return target(J);
    case Triangle::kFocus:
      return Eigen::Matrix2d::Identity();
    case Triangle::kBounded:
      break;
  }
  // Project the singular values (s1, s2), s1 >= |s2|, onto the cone s2 <= s1 <= K s2: inside it
  // J is its own target; otherwise the closest point is on the ray s2 = s1 / K.
  const Eigen::Vector2d s = signed_singular_values(J);
  const double K = t.anisotropy;
  if (s(1) > 0 && s(0) <= K * s(1)) return J;
  const double s2 = std::max(0.0, (K * s(0) + s(1)) / (K * K + 1));
  return with_singular_values(J, K * s2, s2);
}

bool Flattener::keeps_fixed(const Eigen::MatrixX2d& X, const Eigen::MatrixXd& values) const {
  for (Eigen::Index v = 0; v < X.rows(); ++v) {
    if ((fix_x_[size_t(v)] && X(v, 0) != values(v, 0)) ||
        (fix_y_[size_t(v)] && X(v, 1) != values(v, 1)))
      return false;
  }
  return true;
}

bool Flattener::admissible(const Eigen::MatrixX2d& X) const {
  require(X.rows() == rest_.rows(), "Flattener::admissible", "one row per vertex expected");
  return keeps_fixed(X, rest_) && count_folds(X, F_) == 0;
}

void Flattener::admit_anisotropy(const Eigen::MatrixX2d& X) {
  require(X.rows() == rest_.rows(), "Flattener::admit_anisotropy", "one row per vertex expected");
  for (size_t f = 0; f < triangles_.size(); ++f) {
    Triangle& t = triangles_[f];
    if (t.kind != Triangle::kBounded) continue;
    const Eigen::Vector2d s = signed_singular_values(jacobian(t, int(f), X));
    if (s(1) > 0) t.anisotropy = std::max(t.anisotropy, s(0) / s(1));
  }
}

double Flattener::energy(const Eigen::MatrixX2d& X) const {
  double e = 0;
  for (size_t f = 0; f < triangles_.size(); ++f) {
    const Triangle& t = triangles_[f];
    const Eigen::Matrix2d J = jacobian(t, int(f), X);
    e += t.area2c * (J - target(t, J)).squaredNorm();
  }
  return e;
}

double Flattener::max_orientation_step(const Eigen::MatrixX2d& X,
                                       const Eigen::MatrixX2d& next) const {
  // det(A + s B) = det A + s (a00 b11 + a11 b00 - a01 b10 - a10 b01) + s^2 det B for the edge
  // matrices A of X and B of next - X; the first positive root bounds the step.
  double s_max = std::numeric_limits<double>::infinity();
  std::mutex s_max_mutex;
  parallel_for(
      *pool_, size_t(F_.rows()),
      [&](size_t begin, size_t end) {
        double chunk_max = std::numeric_limits<double>::infinity();
        for (Eigen::Index f = Eigen::Index(begin); f < Eigen::Index(end); ++f) {
          Eigen::Matrix2d A, B;
          for (int k = 0; k < 2; ++k) {
            A.col(k) = (X.row(F_(f, k + 1)) - X.row(F_(f, 0))).transpose();
            B.col(k) = (next.row(F_(f, k + 1)) - next.row(F_(f, 0))).transpose() - A.col(k);
          }
          const double c = A.determinant();
          if (c <= 0) continue;  // already degenerate or flipped: the bound cannot help it
          const double b =
              A(0, 0) * B(1, 1) + A(1, 1) * B(0, 0) - A(0, 1) * B(1, 0) - A(1, 0) * B(0, 1);
          const double a = B.determinant();
          double root = std::numeric_limits<double>::infinity();
          if (std::abs(a) < 1e-300) {
            if (b < 0) root = -c / b;
          } else {
            const double disc = b * b - 4 * a * c;
            if (disc >= 0) {
              const double q = std::sqrt(disc);
              for (double s : {(-b - q) / (2 * a), (-b + q) / (2 * a)})
                if (s > 0) root = std::min(root, s);
            }
          }
          chunk_max = std::min(chunk_max, root);
        }
        const std::lock_guard<std::mutex> lock(s_max_mutex);
        s_max = std::min(s_max, chunk_max);
      },
      16384);  // a few dozen flops per triangle: threads only for large meshes
  return s_max > 1.0 ? 1.0 : std::min(1.0, 0.9 * s_max);
}

double Flattener::local_step(const Eigen::MatrixX2d& X, LocalFit& fit) const {
  parallel_for(*pool_, triangles_.size(), [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f) {
      const Triangle& t = triangles_[f];
      const Eigen::Matrix2d J = jacobian(t, int(f), X);
      fit.folded[f] = J.determinant() <= 0;
      const Eigen::Matrix2d M = target(t, J);
      fit.energy[f] = t.area2c * (J - M).squaredNorm();
      const Eigen::Vector2d s[3] = {Eigen::Vector2d::Zero(), t.S.col(0), t.S.col(1)};
      Eigen::Vector2d* q = &fit.share[3 * f];
      q[0] = q[1] = q[2] = Eigen::Vector2d::Zero();
      for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, c = (k + 2) % 3;
        const Eigen::Vector2d d = t.w(k) * (M * (s[a] - s[c]));
        q[a] += d;
        q[c] -= d;
      }
    }
  });
  return std::accumulate(fit.energy.begin(), fit.energy.end(), 0.0);
}

double Flattener::negligible_energy() const {
  // An energy this small relative to the total weight is the exact solution up to rounding.
  double total_weight = 0, bounded_weight = 0;
  for (const Triangle& t : triangles_) {
    total_weight += t.area2c;
    if (t.kind == Triangle::kBounded) bounded_weight += t.area2c;
  }
  // Bounded-distortion targets make the energy the distance to a feasible map, which falls
  // geometrically to 0: it is met once the context's mean squared misfit is tolerance^2.
  return std::max(1e-20 * total_weight, options_.tolerance * options_.tolerance * bounded_weight);
}

Eigen::MatrixXd Flattener::right_hand_side(const std::vector<Eigen::Vector2d>& share) const {
  const Eigen::Index n = rest_.rows();
  Eigen::MatrixXd b(n, 2);
  for (size_t v = 0; v < size_t(n); ++v) {  // a few additions each: not worth a thread
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (int k = corner_start_[v]; k < corner_start_[v + 1]; ++k) sum += share[corner_[k]];
    b.row(Eigen::Index(v)) = sum.transpose();
  }
  return b;
}

Eigen::MatrixX2d Flattener::global_step(const Eigen::MatrixXd& b,
                                        const Eigen::MatrixXd& fixed_values) const {
  factorize();  // the first global step needs it; a start already at the minimum does not
  Eigen::MatrixX2d next(rest_.rows(), 2);
  if (solver_y_) {
    parallel_invoke(
        *pool_, [&] { next.col(0) = solver_x_->solve(b.col(0), fixed_values.col(0)); },
        [&] { next.col(1) = solver_y_->solve(b.col(1), fixed_values.col(1)); });
  } else {
    next = solver_x_->solve(b, fixed_values);
  }
  return next;
}

FlattenResult Flattener::solve(const Eigen::MatrixX2d& X0, const Eigen::MatrixX2d* guess,
                               const SolveControl* control) const {
  require(X0.rows() == rest_.rows(), "Flattener::solve",
          "initial guess has " + std::to_string(X0.rows()) + " rows, expected " +
              std::to_string(rest_.rows()));
  require(guess == nullptr || guess->rows() == X0.rows(), "Flattener::solve",
          "the second guess must have as many rows as the first");
  FlattenResult r;
  r.X = guess ? *guess : X0;
  LocalFit fit(triangles_.size());
  // The guess starts unless it folds a triangle (a flip-safe step cannot unfold it).
  r.energy.push_back(local_step(r.X, fit));
  if (guess && std::find(fit.folded.begin(), fit.folded.end(), 1) != fit.folded.end()) {
    r.X = X0;
    r.energy.back() = local_step(r.X, fit);
  }
  // Fixed coordinates keep the grid's positions; in free mode vertex 0 keeps the start's.
  const Eigen::MatrixXd fixed_values = options_.boundary == Boundary::kFree ? r.X : rest_;
  const double negligible = negligible_energy();
  // A start off its fixed values (a guess that moved a pinned or border vertex) takes at least
  // one global step, which puts them back, however low its energy.
  const bool off_fixed = !keeps_fixed(r.X, fixed_values);
  auto report = [&] {
    if (control) control->step({0, r.iterations, r.energy.back()}, "Flattener::solve");
  };
  report();
  while (r.iterations < options_.max_iterations) {
    if (r.energy.back() <= negligible && !(off_fixed && r.iterations == 0)) {
      r.converged = true;
      break;
    }
    // The global step: the corners' shares gathered per vertex, solved with the fixed values.
    Eigen::MatrixX2d next = global_step(right_hand_side(fit.share), fixed_values);
    // Flip-safe: only as far toward it as keeps every triangle's orientation.
    const double step = options_.flip_safe ? max_orientation_step(r.X, next) : 1.0;
    if (step < 1.0) {
      ++r.bounded_steps;
      r.X += step * (next - r.X);
    } else {
      r.X = std::move(next);
    }
    ++r.iterations;
    // The local step: the targets fitted to the new positions.
    const double previous = r.energy.back();
    r.energy.push_back(local_step(r.X, fit));
    report();
    if (std::abs(previous - r.energy.back()) <= options_.tolerance * previous) {
      r.converged = true;
      break;
    }
  }
  return r;
}

FlattenResult flatten(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                      const Eigen::VectorXd& level, const std::vector<uint8_t>& sides,
                      const FlattenOptions& options, const Eigen::VectorXd& log_scale) {
  return Flattener(V3, F, level, sides, options, log_scale).solve(V3.leftCols<2>());
}

}  // namespace geolens
