#pragma once
// Private: texture coordinates on the lifted mesh, a harmonic map onto the source image (paper
// 4.1); its weights are an option (lens_options.h).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "geolens/lens/lens_options.h"

namespace geolens {

/// Triangles of F whose texture coordinates (#V x 2) are inverted or degenerate.
int count_folds(const Eigen::MatrixX2d& uv, const Eigen::MatrixX3i& F);

/// Weight matrix W (#V x #V, row i holds w_ij for the neighbours j of vertex i, zero diagonal)
/// of the harmonic equation sum_j w_ij (u_i - u_j) = 0, computed on the 3D mesh.
/// @param V3  #V x 3 lifted vertices, pixels
/// @param F   #F x 3 triangles
Eigen::SparseMatrix<double> harmonic_weights(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                                             TextureWeights weights);

/// Solves the harmonic map as one sparse linear system (the fixed point of the paper's
/// Jacobi-style iteration): vertices with `fixed[i] != 0` keep `uv.row(i)`, the others satisfy
/// sum_j w_ij (u_i - u_j) = 0. The paper fixes the image border and every vertex outside all
/// regions of interest.
/// @param uv  #V x 2 initial / boundary texture coordinates (source pixels)
/// @return    #V x 2 texture coordinates, source pixels
Eigen::MatrixX2d harmonic_texture(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                                  const std::vector<char>& fixed, const Eigen::MatrixX2d& uv,
                                  TextureWeights weights);

}  // namespace geolens
