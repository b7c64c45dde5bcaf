#include "geolens/core/errors.h"

namespace geolens {

void require(bool condition, const char* function, const std::string& what) {
  if (!condition) throw InvalidInput(std::string(function) + ": " + what);
}

}  // namespace geolens
