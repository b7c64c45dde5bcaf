#include "lens/texture_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geolens/geometry/grid.h"

namespace geolens {
namespace {

// A flat grid, its border fixed, the interior started anywhere: every weight family has linear
// precision on a flat mesh, so the harmonic map is the identity.
TEST(HarmonicTexture, AFlatMeshMapsToItself) {
  const Grid grid = make_grid(300, 200, 16);
  Eigen::MatrixX3d V3 = Eigen::MatrixX3d::Zero(grid.V.rows(), 3);
  V3.leftCols<2>() = grid.V;
  std::vector<char> fixed(grid.sides.begin(), grid.sides.end());
  Eigen::MatrixX2d start = grid.V;
  for (Eigen::Index i = 0; i < start.rows(); ++i)
    if (!fixed[size_t(i)]) start.row(i) = Eigen::RowVector2d(150, 100);
  for (const auto weights :
       {TextureWeights::kMeanValue, TextureWeights::kCotan, TextureWeights::kPositiveCotan}) {
    SCOPED_TRACE(to_string(weights));
    const Eigen::MatrixX2d uv = harmonic_texture(V3, grid.F, fixed, start, weights);
    EXPECT_LT((uv - grid.V).cwiseAbs().maxCoeff(), 1e-8);
  }
}

// On a bump, the interior's texture satisfies the harmonic equation row by row, fixed vertices
// keep their values, and the non-negative weights fold nothing.
TEST(HarmonicTexture, EveryFreeRowSatisfiesTheHarmonicEquation) {
  const Grid grid = make_grid(200, 200, 21);
  Eigen::MatrixX3d V3(grid.V.rows(), 3);
  V3.leftCols<2>() = grid.V;
  std::vector<char> fixed(size_t(grid.V.rows()));
  for (Eigen::Index i = 0; i < grid.V.rows(); ++i) {
    const double r = (grid.V.row(i) - Eigen::RowVector2d(100, 100)).norm() / 70;
    V3(i, 2) = r < 1 ? 80 * (1 - r * r) * (1 - r * r) : 0;
    fixed[size_t(i)] = r >= 1;
  }
  for (const auto weights :
       {TextureWeights::kMeanValue, TextureWeights::kCotan, TextureWeights::kPositiveCotan}) {
    SCOPED_TRACE(to_string(weights));
    const Eigen::MatrixX2d uv = harmonic_texture(V3, grid.F, fixed, grid.V, weights);
    const Eigen::SparseMatrix<double> W = harmonic_weights(V3, grid.F, weights);
    const Eigen::VectorXd degree = W * Eigen::VectorXd::Ones(W.cols());
    const Eigen::MatrixX2d residual = degree.asDiagonal() * uv - W * uv;
    for (Eigen::Index i = 0; i < uv.rows(); ++i) {
      if (fixed[size_t(i)]) {
        EXPECT_EQ(uv.row(i), grid.V.row(i));
      } else {
        EXPECT_LT(residual.row(i).norm(), 1e-8 * degree(i) * 200);
      }
    }
    if (weights == TextureWeights::kPositiveCotan) EXPECT_EQ(count_folds(uv, grid.F), 0);
  }
}

}  // namespace
}  // namespace geolens
