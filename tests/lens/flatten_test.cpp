#include "lens/flatten.h"

#include <gtest/gtest.h>

#include "geolens/core/errors.h"
#include "geolens/geometry/grid.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/measure/distortion.h"
#include "lens/lift.h"
#include "support/lens_options.h"

namespace geolens {
namespace {

Lens centred_lens(double size, double radius) {
  return Lens{Region::circle({size / 2, size / 2}, radius)};
}

// A 400 px image on a 41-vertex grid with a gaussian bump of height h0 = r at the centre.
struct Bump {
  Grid grid = make_grid(400, 400, 41);
  Lifted lifted = lift(grid.V, {centred_lens(400, 100)}, {100.0});
};

TEST(Flattener, GlobalMatrixIsASymmetricLaplacian) {
  const Bump b;
  for (FlattenWeights w : {FlattenWeights::kPaper, FlattenWeights::kCotan}) {
    FlattenOptions o;
    o.weights = w;
    const Flattener flattener(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, o);
    const Eigen::SparseMatrix<double>& L = flattener.laplacian();
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(L.cols());
    EXPECT_LT((L * ones).cwiseAbs().maxCoeff(), 1e-9 * L.diagonal().maxCoeff());
    EXPECT_LT((L - Eigen::SparseMatrix<double>(L.transpose())).norm(), 1e-12 * L.norm());
    EXPECT_GT(L.diagonal().minCoeff(), 0);
  }
}

TEST(Flattener, FlatMeshIsAlreadyTheMinimum) {
  const Grid grid = make_grid(300, 200, 31);
  const Lifted flat = lift(grid.V, {}, {});
  for (Boundary boundary : {Boundary::kSliding, Boundary::kFixed, Boundary::kFree}) {
    FlattenOptions o;
    o.boundary = boundary;
    const FlattenResult r = flatten(flat.V, grid.F, flat.level, grid.sides, o);
    EXPECT_TRUE(r.converged);
    EXPECT_LE(r.iterations, 1);
    EXPECT_LT((r.X - grid.V).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(Flattener, ArapEnergyNeverIncreases) {
  const Bump b;
  FlattenOptions o;
  o.weights = FlattenWeights::kCotan;
  o.tolerance = 1e-9;
  o.max_iterations = 50;
  const FlattenResult r = flatten(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, o);
  ASSERT_GE(r.energy.size(), 3u);
  EXPECT_LT(r.energy.back(), 0.9 * r.energy.front());
  for (size_t k = 1; k < r.energy.size(); ++k)
    EXPECT_LE(r.energy[k], r.energy[k - 1] * (1 + 1e-12)) << "iteration " << k;
}

TEST(Flattener, SlidingBorderStaysOnItsSides) {
  const Bump b;
  const FlattenResult r = flatten(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, {});
  for (size_t i = 0; i < b.grid.sides.size(); ++i) {
    const uint8_t s = b.grid.sides[i];
    if (s & kLeft) EXPECT_EQ(r.X(Eigen::Index(i), 0), 0);
    if (s & kRight) EXPECT_EQ(r.X(Eigen::Index(i), 0), 400);
    if (s & kTop) EXPECT_EQ(r.X(Eigen::Index(i), 1), 0);
    if (s & kBottom) EXPECT_EQ(r.X(Eigen::Index(i), 1), 400);
  }
  // The bump pushed the context outward: the border vertices in the middle of a side moved
  // along it only; interior vertices near the border moved too.
  EXPECT_GT((r.X - b.grid.V).rowwise().norm().maxCoeff(), 1.0);
}

// Runs the lens with fixed heights (no calibration, so only the metric differs).
LensResult run(Metric metric, double alpha, double tolerance) {
  LensOptions o = test::auto_model();
  o.mesh = 41;
  o.flatten.metric = metric;
  o.flatten.alpha = alpha;
  o.flatten.tolerance = tolerance;
  o.flatten.max_iterations = 20000;
  return GeometricLens(400, 400, o).solve_with_heights({centred_lens(400, 100)}, {100.0});
}

TEST(Flattener, PaperAlphaConvergesToTheSameResult) {
  const LensResult reference = run(Metric::kPaper, 0.0, 1e-11);
  const LensResult early_reference = run(Metric::kPaper, 0.0, 1e-3);
  for (double alpha : {0.1, 0.5}) {
    const LensResult r = run(Metric::kPaper, alpha, 1e-11);
    EXPECT_TRUE(r.flattening.converged);
    const double converged_gap = (r.flat - reference.flat).cwiseAbs().maxCoeff();
    EXPECT_LT(converged_gap, 0.01) << "alpha " << alpha;
    EXPECT_NEAR(r.zoom_measured[0], reference.zoom_measured[0], 1e-3);
    // Stopped at the paper's 0.1 %, the blend does change the result (its Fig. 6).
    const LensResult early = run(Metric::kPaper, alpha, 1e-3);
    EXPECT_GT((early.flat - early_reference.flat).cwiseAbs().maxCoeff(), 10 * converged_gap)
        << "alpha " << alpha;
  }
}

TEST(Flattener, SpectrumChangesTheConvergedResultMonotonically) {
  double previous_conformal = 1e9, previous_zoom = 1e9;
  for (double alpha : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const LensResult r = run(Metric::kSpectrum, alpha, 1e-9);
    EXPECT_TRUE(r.flattening.converged) << alpha;
    // Shape distortion of the warp falls from rigid (ARAP) to angle-preserving (ASAP).
    const double conformal = summarize(measure_triangles(r.warp)).conformal_mean;
    EXPECT_LT(conformal, previous_conformal) << "alpha " << alpha;
    EXPECT_LT(r.zoom_measured[0], previous_zoom) << "alpha " << alpha;
    previous_conformal = conformal;
    previous_zoom = r.zoom_measured[0];
  }
}

int flipped(const Eigen::MatrixX2d& X, const Eigen::MatrixX3i& F) {
  int count = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d a = X.row(F(f, 0)), b = X.row(F(f, 1)), c = X.row(F(f, 2));
    count += (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() <= 0;
  }
  return count;
}

// A bump twice as tall as wide: the plain local/global iteration folds triangles.
TEST(Flattener, FlipSafeStepKeepsEveryOrientation) {
  const Grid grid = make_grid(400, 400, 41);
  const Lifted tall = lift(grid.V, {centred_lens(400, 100)}, {200.0});
  FlattenOptions o;
  o.tolerance = 1e-6;
  o.max_iterations = 200;
  o.flip_safe = false;
  const FlattenResult unsafe = flatten(tall.V, grid.F, tall.level, grid.sides, o);
  ASSERT_GT(flipped(unsafe.X, grid.F), 0);
  o.flip_safe = true;
  const FlattenResult safe = flatten(tall.V, grid.F, tall.level, grid.sides, o);
  EXPECT_EQ(flipped(safe.X, grid.F), 0);
  EXPECT_GT(safe.bounded_steps, 0);
  for (size_t k = 1; k < safe.energy.size(); ++k) EXPECT_LE(safe.energy[k], safe.energy[k - 1]);
  // The price of keeping orientations is small.
  EXPECT_LT(safe.energy.back(), 1.02 * unsafe.energy.back());
}

TEST(Flattener, RejectsBadOptions) {
  const Bump b;
  FlattenOptions o;
  o.alpha = -0.1;
  EXPECT_THROW(Flattener(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, o), InvalidInput);
  o.alpha = 1.0;  // the paper blend at 1 fits every triangle to itself
  EXPECT_THROW(Flattener(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, o), InvalidInput);
  o = {};
  o.tolerance = 0;
  EXPECT_THROW(Flattener(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, o), InvalidInput);
  o = {};
  o.max_iterations = 0;
  EXPECT_THROW(Flattener(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, o), InvalidInput);
  o = {};
  o.threads = -1;
  EXPECT_THROW(Flattener(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, o), InvalidInput);
}

// A second guess starts the solve unless it folds a triangle.
TEST(Flattener, StartsFromTheGuessUnlessItFolds) {
  const Bump b;
  const Flattener flattener(b.lifted.V, b.grid.F, b.lifted.level, b.grid.sides, {});
  const Eigen::MatrixX2d projection = b.grid.V;
  const FlattenResult solved = flattener.solve(projection);
  ASSERT_TRUE(solved.converged);
  // The converged flattening as the guess: taken, so the start's energy is its energy and the
  // solve stops at once.
  const FlattenResult from_guess = flattener.solve(projection, &solved.X);
  EXPECT_NEAR(from_guess.energy.front(), flattener.energy(solved.X), 1e-9 * solved.energy.back());
  EXPECT_LE(from_guess.iterations, 1);
  // A fold-free guess is taken even when worse than X0: the result converges all the same.
  const Eigen::MatrixX2d worse = projection + 0.3 * (projection - solved.X);
  const FlattenResult from_worse = flattener.solve(projection, &worse);
  EXPECT_NEAR(from_worse.energy.front(), flattener.energy(worse), 1e-9 * from_worse.energy.front());
  EXPECT_TRUE(from_worse.converged);
  EXPECT_NEAR(from_worse.energy.back() / solved.energy.back(), 1.0, 0.01);
  // A folded guess is refused: the minimum with two vertices of one triangle swapped.
  Eigen::MatrixX2d folded = solved.X;
  const int v = b.grid.F(b.grid.F.rows() / 2, 0);
  const int w = b.grid.F(b.grid.F.rows() / 2, 1);
  folded.row(v).swap(folded.row(w));
  const FlattenResult refused = flattener.solve(projection, &folded);
  EXPECT_EQ(refused.energy, solved.energy);
  const Eigen::MatrixX2d short_guess = folded.topRows(3);
  EXPECT_THROW(flattener.solve(projection, &short_guess), InvalidInput);
}

}  // namespace
}  // namespace geolens
