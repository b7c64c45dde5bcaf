#include "lens/texture_map.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "geolens/core/errors.h"
#include "numerics/sparse_solver.h"

namespace geolens {

int count_folds(const Eigen::MatrixX2d& uv, const Eigen::MatrixX3i& F) {
  int folds = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d a = uv.row(F(f, 0)), b = uv.row(F(f, 1)), c = uv.row(F(f, 2));
    folds += (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() <= 0;
  }
  return folds;
}

Eigen::SparseMatrix<double> harmonic_weights(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                                             TextureWeights weights) {
  std::vector<Eigen::Triplet<double>> w;
  w.reserve(size_t(F.rows()) * 6);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      // Corner i with the other two vertices j, l of the triangle.
      const int i = F(t, k), j = F(t, (k + 1) % 3), l = F(t, (k + 2) % 3);
      const Eigen::Vector3d a = V3.row(j) - V3.row(i), b = V3.row(l) - V3.row(i);
      const double la = a.norm(), lb = b.norm();
      const double cos_angle = a.dot(b), sin_angle = a.cross(b).norm();
      if (weights != TextureWeights::kMeanValue) {
        // cot of the angle at i weighs the opposite edge (j, l), half per triangle.
        double c = 0.5 * cos_angle / sin_angle;
        if (weights == TextureWeights::kPositiveCotan) c = std::max(0.0, c);
        w.emplace_back(j, l, c);
        w.emplace_back(l, j, c);
      } else {
        // tan(angle / 2) = sin / (1 + cos) with unit vectors; weighs edges (i, j) and (i, l).
        const double tan_half = sin_angle / (la * lb + cos_angle);
        w.emplace_back(i, j, tan_half / la);
        w.emplace_back(i, l, tan_half / lb);
      }
    }
  }
  Eigen::SparseMatrix<double> W(V3.rows(), V3.rows());
  W.setFromTriplets(w.begin(), w.end());
  return W;
}

Eigen::MatrixX2d harmonic_texture(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                                  const std::vector<char>& fixed, const Eigen::MatrixX2d& uv,
                                  TextureWeights weights) {
  require(uv.rows() == V3.rows() && fixed.size() == size_t(V3.rows()), "harmonic_texture",
          "uv and fixed flags must have one row per vertex");
  if (std::all_of(fixed.begin(), fixed.end(), [](char f) { return f != 0; })) return uv;
  // Only the rows of free vertices matter: weigh the triangles that touch one.
  std::vector<Eigen::Index> touching;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (!fixed[size_t(F(f, 0))] || !fixed[size_t(F(f, 1))] || !fixed[size_t(F(f, 2))])
      touching.push_back(f);
  const Eigen::SparseMatrix<double> W = harmonic_weights(V3, F(touching, Eigen::all), weights);
  // Row i: sum_j w_ij (u_i - u_j) = 0, the Laplacian L = diag(W 1) - W, on the free rows (the
  // rows of fixed vertices, which the untouched triangles leave empty, are not solved).
  const Eigen::VectorXd degree = W * Eigen::VectorXd::Ones(W.cols());
  const Eigen::SparseMatrix<double> L = Eigen::SparseMatrix<double>(degree.asDiagonal()) - W;
  // Mean value weights are not symmetric.
  const DirichletSolver solver(L, fixed,
                               weights == TextureWeights::kMeanValue
                                   ? DirichletSolver::Matrix::kGeneral
                                   : DirichletSolver::Matrix::kSymmetric);
  return solver.solve(Eigen::MatrixXd::Zero(uv.rows(), 2), uv);
}

}  // namespace geolens
