#pragma once
// Closed-form signed singular value decomposition of a 2x2 matrix.

#include <Eigen/Core>

namespace geolens {

/// J = Rot(phi) * diag(s1, s2) * Rot(theta) with s1 >= |s2| and s2 < 0 exactly when
/// det J < 0 (the reflection is carried by s2, so both factors are rotations).
struct SignedSvd2 {
  double s1 = 0, s2 = 0;                                 ///< signed singular values
  double phi = 0, theta = 0;                             ///< rotation angles, radians
  double rotation_angle() const { return phi + theta; }  ///< angle of the closest rotation
};

SignedSvd2 signed_svd(const Eigen::Matrix2d& J);

/// Rot(phi) * diag(a, b) * Rot(theta): the factors of `svd` with new singular values.
Eigen::Matrix2d compose(const SignedSvd2& svd, double a, double b);

/// The 2x2 rotation by `angle` radians.
Eigen::Matrix2d rotation(double angle);

}  // namespace geolens
