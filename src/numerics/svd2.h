#pragma once
// Closed-form signed singular value decomposition of a 2x2 matrix.

#include <Eigen/Core>

namespace geolens {

/// J = Rot(phi) * diag(s1, s2) * Rot(theta) with s1 >= |s2| and s2 < 0 exactly when
/// det J < 0 (the reflection is carried by s2, so both factors are rotations).
struct SignedSvd2 {
  double s1 = 0, s2 = 0;      ///< signed singular values
  double phi = 0, theta = 0;  ///< rotation angles, radians; phi + theta: the closest rotation
};

/// The entries of J must be below about 1e150 in magnitude (their squares are summed), as any
/// Jacobian of a warp in pixels is.
SignedSvd2 signed_svd(const Eigen::Matrix2d& J);

/// signed_svd's (s1, s2) alone, without the angles (no trigonometry).
Eigen::Vector2d signed_singular_values(const Eigen::Matrix2d& J);

/// Rot(phi) * diag(x, y) * Rot(theta) for signed_svd(J)'s angles, without computing them:
/// J with its signed singular values replaced by x and y.
Eigen::Matrix2d with_singular_values(const Eigen::Matrix2d& J, double x, double y);

}  // namespace geolens
