#pragma once
// The options of the tests written for the lift and field models: LensModel::kAuto, the
// default before the focus model (lift for circles, field for other regions).

#include "geolens/lens/geometric_lens.h"

namespace geolens::test {

inline LensOptions auto_model(LensOptions options = {}) {
  options.model = LensModel::kAuto;
  return options;
}

}  // namespace geolens::test
