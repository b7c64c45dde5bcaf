#pragma once
// Private to eval/: numbers written as the comparison's labels and reports write them.

#include <cstdio>
#include <string>

namespace geolens {

/// `value` with `digits` digits after the point ("%.*f").
inline std::string fixed_text(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

}  // namespace geolens
