#include "geolens/numerics/svd2.h"

#include <cmath>

namespace geolens {

// With E = (a + d) / 2, F = (a - d) / 2, G = (c + b) / 2, H = (c - b) / 2 for J = [a b; c d],
// J = Rot(phi) diag(Q + R, Q - R) Rot(theta) where Q = |(E, H)|, R = |(F, G)|,
// phi = (atan2(H, E) + atan2(G, F)) / 2, theta = (atan2(H, E) - atan2(G, F)) / 2
// (J. Blinn, "Consider the lowly 2x2 matrix", IEEE CG&A 1996).
SignedSvd2 signed_svd(const Eigen::Matrix2d& J) {
  const double E = 0.5 * (J(0, 0) + J(1, 1)), F = 0.5 * (J(0, 0) - J(1, 1));
  const double G = 0.5 * (J(1, 0) + J(0, 1)), H = 0.5 * (J(1, 0) - J(0, 1));
  const double Q = std::hypot(E, H), R = std::hypot(F, G);
  const double a1 = std::atan2(G, F), a2 = std::atan2(H, E);
  SignedSvd2 s;
  s.s1 = Q + R;
  s.s2 = Q - R;
  s.phi = 0.5 * (a2 + a1);
  s.theta = 0.5 * (a2 - a1);
  return s;
}

}  // namespace geolens
