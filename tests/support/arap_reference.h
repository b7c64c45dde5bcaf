#pragma once
// An independent reference for the as-rigid-as-possible (ARAP) flattening energy, for tests.
// Written from the definition and sharing no code with the library's flattener; it also uses
// different methods on purpose (a closed-form 2x2 closest rotation instead of an SVD, plain
// gradient descent instead of local/global iterations), so agreement between the two means
// something.
//
// The energy of a flat mesh X relative to a 3D mesh V3 with the same triangles F is
//
//   E(X) = sum_t A_t ||J_t - R_t||_F^2
//
// A_t: area of triangle t in V3. J_t: 2x2 Jacobian of the affine map from t's standard triangle
// (its isometric 2D copy: first vertex at the origin, second on the +x axis, third at y > 0) to
// its image in X. R_t: the rotation (det +1) closest to J_t in the Frobenius norm. E is invariant
// to rigid motions of X; it is 0 exactly when every triangle of X is a rotated and translated
// copy of its standard triangle, and a mirrored triangle (det J_t < 0) always costs energy.
// Equivalently, E = sum_t sum_{edges ij of t} cot(theta_ij) ||x_i - x_j - R_t (s_i - s_j)||^2 / 2,
// theta_ij the angle of t opposite the edge and s the standard triangle's vertices.

#include <Eigen/Core>
#include <string>

namespace geolens::testing {

/// The ARAP energy E(X) above.
/// @param V3 #V x 3 vertex positions of the 3D mesh, any length unit L, finite
/// @param F  #F x 3 triangles, 0-based vertex indices; no triangle may be degenerate in V3
/// @param X  #V x 2 flat vertex positions, unit L, finite
/// @return E, unit L^2
/// @throws std::invalid_argument on a size mismatch, an index out of range, a non-finite
///         coordinate or a degenerate triangle; the message names the function and the value
double arap_energy(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                   const Eigen::MatrixX2d& X);

/// The gradient dE/dX of arap_energy, analytic: per triangle dE/dJ = 2 A (J - R) (the rotation's
/// own variation does not contribute at the closest rotation), chained through J = D S^-1 with
/// D = [x2 - x1, x3 - x1] and S the standard triangle's edge matrix.
/// Where J_t has no unique closest rotation (J_t = [a b; b -a]) E is not differentiable; there
/// this takes R_t = identity.
/// @return #V x 2, unit L; its columns sum to 0 (E is invariant to translation)
/// @throws std::invalid_argument as arap_energy
Eigen::MatrixX2d arap_gradient(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                               const Eigen::MatrixX2d& X);

/// Lowers E from X0 by plain gradient descent with a backtracking (Armijo) line search. A step is
/// accepted only if it lowers E by at least 1e-4 of the linear prediction, so E never rises:
/// E(result) <= E(X0). The descent stops early once even a step too small to move any vertex
/// would be needed (no decrease along the gradient is measurable any more). No vertex is pinned:
/// E is invariant to translation, so its gradient has zero mean (the round-off part is projected
/// out) and the descent keeps the centroid where X0 had it.
/// Slow (linear convergence) but simple, and independent of any local/global solver.
/// @param X0 #V x 2 starting flat positions, unit L
/// @param iterations number of gradient steps, >= 0
/// @return #V x 2 descended positions, unit L
/// @throws std::invalid_argument as arap_energy, or if iterations < 0
Eigen::MatrixX2d arap_descend(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                              const Eigen::MatrixX2d& X0, int iterations);

/// Reads a triangle mesh from a Wavefront OBJ file: `v x y z` lines give V, `f a b c` lines give
/// F, with 1-based vertex references that may carry texture / normal references (`a/b`, `a//c`,
/// `a/b/c`; only the vertex index is kept). Blank lines, `#` comments and the statements that do
/// not change the geometry (vt, vn, o, g, s, usemtl, mtllib) are skipped.
/// @param path file to read
/// @param V    out: #V x 3 vertex positions
/// @param F    out: #F x 3 triangles, 0-based vertex indices
/// @throws std::runtime_error if the file cannot be read or is malformed: any other statement, a
///         vertex without exactly 3 finite coordinates, a face without exactly 3 vertices, a
///         vertex index out of range; the message names the file, line and offending text
void read_obj(const std::string& path, Eigen::MatrixX3d& V, Eigen::MatrixX3i& F);

}  // namespace geolens::testing
