#include "geolens/numerics/svd2.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <random>

namespace geolens {
namespace {

Eigen::Matrix2d rotation(double angle) {
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return R;
}

Eigen::Matrix2d compose(const SignedSvd2& s) {
  return rotation(s.phi) * Eigen::Vector2d(s.s1, s.s2).asDiagonal() * rotation(s.theta);
}

TEST(SignedSvd2, ReconstructsAndMatchesEigen) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix2d J;
    J << u(rng), u(rng), u(rng), u(rng);
    const SignedSvd2 s = signed_svd(J);
    EXPECT_LT((compose(s) - J).norm(), 1e-12);
    const Eigen::Vector2d sv = J.jacobiSvd().singularValues();
    EXPECT_NEAR(s.s1, sv(0), 1e-12);
    EXPECT_NEAR(std::abs(s.s2), sv(1), 1e-12);
    EXPECT_EQ(s.s2 < 0, J.determinant() < 0);
  }
}

TEST(SignedSvd2, RotationAngleIsTheClosestRotation) {
  Eigen::Matrix2d J = rotation(0.7) * Eigen::Vector2d(2.0, 0.5).asDiagonal() * rotation(-0.2);
  const SignedSvd2 s = signed_svd(J);
  const Eigen::Matrix2d R = rotation(s.phi + s.theta);
  // No other rotation is closer.
  for (double a = -3.1; a < 3.1; a += 0.01)
    EXPECT_LE((J - R).norm(), (J - rotation(a)).norm() + 1e-12);
}

}  // namespace
}  // namespace geolens
