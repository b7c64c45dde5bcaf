#include "numerics/svd2.h"

#include <cmath>

namespace geolens {

namespace {

// With E = (a + d) / 2, F = (a - d) / 2, G = (c + b) / 2, H = (c - b) / 2 for J = [a b; c d],
// J = Rot(phi) diag(Q + R, Q - R) Rot(theta) where Q = |(E, H)|, R = |(F, G)|,
// phi = (atan2(H, E) + atan2(G, F)) / 2, theta = (atan2(H, E) - atan2(G, F)) / 2
// (J. Blinn, "Consider the lowly 2x2 matrix", IEEE CG&A 1996).
struct Parts {
  double E, F, G, H, Q, R;
};

Parts parts(const Eigen::Matrix2d& J) {
  Parts p;
  p.E = 0.5 * (J(0, 0) + J(1, 1));
  p.F = 0.5 * (J(0, 0) - J(1, 1));
  p.G = 0.5 * (J(1, 0) + J(0, 1));
  p.H = 0.5 * (J(1, 0) - J(0, 1));
  // (Not std::hypot, 3-4 times slower: the entries of a Jacobian are far from over- or
  // underflowing when squared.)
  p.Q = std::sqrt(p.E * p.E + p.H * p.H);
  p.R = std::sqrt(p.F * p.F + p.G * p.G);
  return p;
}

}  // namespace

SignedSvd2 signed_svd(const Eigen::Matrix2d& J) {
  const Parts p = parts(J);
  const double a1 = std::atan2(p.G, p.F), a2 = std::atan2(p.H, p.E);
  SignedSvd2 s;
  s.s1 = p.Q + p.R;
  s.s2 = p.Q - p.R;
  s.phi = 0.5 * (a2 + a1);
  s.theta = 0.5 * (a2 - a1);
  return s;
}

Eigen::Vector2d signed_singular_values(const Eigen::Matrix2d& J) {
  const Parts p = parts(J);
  return Eigen::Vector2d(p.Q + p.R, p.Q - p.R);
}

// Rot(phi) diag(x, y) Rot(theta) = (x + y) / 2 Rot(phi + theta) + (x - y) / 2 Rot(phi) diag(1, -1)
// Rot(theta), and diag(1, -1) Rot(theta) = Rot(-theta) diag(1, -1), so the second term is the
// reflection of angle phi - theta = atan2(G, F): [F G; G -F] / R; the first term's rotation is
// [E -H; H E] / Q (atan2(0, 0) = 0 where Q or R is 0, as in signed_svd).
Eigen::Matrix2d with_singular_values(const Eigen::Matrix2d& J, double x, double y) {
  const Parts p = parts(J);
  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity(), reflection;
  if (p.Q > 0) rotation << p.E / p.Q, -p.H / p.Q, p.H / p.Q, p.E / p.Q;
  if (p.R > 0) {
    reflection << p.F / p.R, p.G / p.R, p.G / p.R, -p.F / p.R;
  } else {
    reflection << 1, 0, 0, -1;
  }
  return 0.5 * (x + y) * rotation + 0.5 * (x - y) * reflection;
}

}  // namespace geolens
