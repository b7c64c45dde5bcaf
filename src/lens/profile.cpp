#include <algorithm>
#include <cmath>

#include "core/enum_names.h"
#include "geolens/core/errors.h"
#include "geolens/lens/lens.h"

namespace geolens {

namespace {
constexpr double kSigma = 0.4;
}

double profile_value(Profile profile, double t) {
  t = std::clamp(t, 0.0, 1.0);
  const double s = 1.0 - t;
  switch (profile) {
    case Profile::kGaussian: {
      const double floor = std::exp(-1.0 / (kSigma * kSigma));
      return (std::exp(-s * s / (kSigma * kSigma)) - floor) / (1.0 - floor);
    }
    case Profile::kSphere:
      return std::sqrt(std::max(0.0, 1.0 - s * s));
    case Profile::kMesa: {
      const double u = std::min(1.0, 2.0 * t);
      return u * u * (3.0 - 2.0 * u);
    }
  }
  return 0.0;
}

namespace {
constexpr EnumName<Profile> kProfiles[] = {
    {Profile::kGaussian, "gaussian"}, {Profile::kSphere, "sphere"}, {Profile::kMesa, "mesa"}};
}  // namespace

Profile parse_profile(const std::string& name) {
  return parse_enum(kProfiles, name, "parse_profile", "profile");
}

std::string to_string(Profile profile) { return enum_name(kProfiles, profile); }

}  // namespace geolens
