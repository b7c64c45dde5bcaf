#pragma once
// Bump profiles: the shape of a lens's 3D lift across its region of interest.

#include <string>

namespace geolens {

/// Profile of the lift, as a function of the normalized depth t in [0, 1] (0 on the ROI
/// boundary, 1 at its centre / medial axis). Every profile is 0 at t = 0, 1 at t = 1 and
/// continuous, so the lift is `h0 * profile(t)` with h0 the height at the centre.
enum class Profile {
  kGaussian,  ///< (exp(-s^2 / sigma^2) - exp(-1 / sigma^2)) / (1 - exp(-1 / sigma^2)), s = 1 - t,
              ///< sigma = 0.4: the paper's gaussian, normalized to 0 at the rim (DESIGN 2.4)
  kSphere,    ///< sqrt(1 - s^2): the paper's hemisphere, scaled to height h0
  kMesa,      ///< flat top for t >= 0.5, smoothstep wall 3u^2 - 2u^3 (u = 2t) below
};

/// profile(t) for t in [0, 1]; t is clamped to that range.
double profile_value(Profile profile, double t);

/// Parses "gaussian", "sphere" or "mesa"; throws InvalidInput otherwise.
Profile parse_profile(const std::string& name);
std::string to_string(Profile profile);

}  // namespace geolens
