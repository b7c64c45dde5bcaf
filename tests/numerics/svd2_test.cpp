#include "numerics/svd2.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <vector>

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

// The angle-free forms agree with signed_svd: the same values, and J rebuilt with other
// singular values through its own rotations (also where J is conformal or an anti-conformal
// reflection, and where it is 0).
TEST(SignedSvd2, AngleFreeFormsMatchTheDecomposition) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3, 3);
  std::vector<Eigen::Matrix2d> cases;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix2d J;
    J << u(rng), u(rng), u(rng), u(rng);
    cases.push_back(J);
  }
  cases.push_back(2 * rotation(0.4));
  Eigen::Matrix2d reflection;
  reflection << 1, 2, 2, -1;
  cases.push_back(reflection);
  cases.push_back(Eigen::Matrix2d::Zero());
  for (const Eigen::Matrix2d& J : cases) {
    const SignedSvd2 s = signed_svd(J);
    const Eigen::Vector2d values = signed_singular_values(J);
    EXPECT_NEAR(values(0), s.s1, 1e-12);
    EXPECT_NEAR(values(1), s.s2, 1e-12);
    const double x = u(rng), y = u(rng);
    const Eigen::Matrix2d expected =
        rotation(s.phi) * Eigen::Vector2d(x, y).asDiagonal() * rotation(s.theta);
    EXPECT_LT((with_singular_values(J, x, y) - expected).norm(), 1e-12);
    EXPECT_LT((with_singular_values(J, s.s1, s.s2) - J).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace geolens
