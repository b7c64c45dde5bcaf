#include "geolens/core/errors.h"

#include <charconv>

namespace geolens {

void require(bool condition, const char* function, const std::string& what) {
  if (!condition) throw InvalidInput(std::string(function) + ": " + what);
}

std::string number_text(double value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

}  // namespace geolens
